#!/usr/bin/env bash
# Installs a plcrun .deb into a clean Debian root made by debootstrap and
# starts what its systemd unit starts, as the unit's user (docs/install.md):
#
#   scripts/package_test.sh target/debian/plcrun_0.1.0-1_amd64.deb
#
# Checks: dpkg -i succeeds (postinst creates the plcrun user), the binary,
# unit, configuration, man pages and completions are where they belong,
# the unit's ExecStart runs the packaged project for 3 s as User=plcrun
# and stops cleanly on SIGTERM with its retained data saved under
# /var/lib/plcrun. Needs root, debootstrap and a Debian mirror; the root
# is cached in target/package-root (PLCRUN_ROOT to put it elsewhere).
set -euo pipefail
deb=$(realpath "$1")
cd "$(dirname "$0")/.."
root=${PLCRUN_ROOT:-$PWD/target/package-root}
if [ ! -x "$root/bin/sh" ]; then
    command -v debootstrap >/dev/null || { echo "debootstrap is needed (apt-get install debootstrap)" >&2; exit 2; }
    rm -rf "$root"
    debootstrap --variant=minbase bookworm "$root" >/dev/null
fi
# A fresh copy for each run, so that every run installs into a clean root.
work=$(mktemp -d)
trap 'umount "$work/root/proc" 2>/dev/null || true; rm -rf "$work"' EXIT
cp -a "$root" "$work/root"
cp "$deb" "$work/root/tmp/plcrun.deb"
mount -t proc proc "$work/root/proc"
chroot "$work/root" apt-get install -y -q /tmp/plcrun.deb >/dev/null 2>&1 \
    || chroot "$work/root" dpkg -i /tmp/plcrun.deb
for f in /usr/bin/plcrun /lib/systemd/system/plcrun.service /etc/plcrun/plcrun.toml \
         /etc/plcrun/main.st /usr/share/man/man1/plcrun.1.gz /usr/share/man/man1/plcrun-serve.1.gz \
         /usr/share/bash-completion/completions/plcrun; do
    [ -e "$work/root$f" ] || { echo "missing after install: $f" >&2; exit 1; }
done
chroot "$work/root" getent passwd plcrun >/dev/null || { echo "postinst made no plcrun user" >&2; exit 1; }
exec_start=$(sed -n 's/^ExecStart=//p' "$work/root/lib/systemd/system/plcrun.service")
user=$(sed -n 's/^User=//p' "$work/root/lib/systemd/system/plcrun.service")
mkdir -p "$work/root/var/lib/plcrun"
chroot "$work/root" chown "$user:$user" /var/lib/plcrun
echo "running as $user: $exec_start"
chroot --userspec="$user:$user" "$work/root" sh -c "cd /var/lib/plcrun && exec $exec_start" &
pid=$!
sleep 3
kill -0 "$pid" || { echo "the service's command exited early" >&2; wait "$pid"; exit 1; }
kill -TERM "$pid"
status=0
wait "$pid" || status=$?
[ "$status" = 0 ] || { echo "SIGTERM: exit status $status, not 0" >&2; exit 1; }
[ -s "$work/root/var/lib/plcrun/plcrun.retain" ] || { echo "no retained data saved on stop" >&2; exit 1; }
echo "package ok: installed, ran 3 s as $user, stopped cleanly, retain saved ($(du -h "$deb" | cut -f1) package)"
