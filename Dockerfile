# plcrun in a container: `plcrun serve` as a non-root user (docs/install.md).
#   docker build -t plcrun .
#   docker run --rm -p 5020:5020 -v "$PWD/myproject:/etc/plcrun:ro" plcrun
# Build stage: the release binary, with the default features (command
# line and OPC UA).
FROM rust:1-bookworm AS build
WORKDIR /src
COPY . .
RUN cargo build --release --locked --bin plcrun \
    && strip target/release/plcrun

# Runtime stage: Debian slim, the binary, the example project, a user.
FROM debian:bookworm-slim
RUN useradd --system --user-group --home-dir /var/lib/plcrun --create-home plcrun
COPY --from=build /src/target/release/plcrun /usr/bin/plcrun
COPY packaging/plcrun.toml packaging/main.st /etc/plcrun/
USER plcrun
WORKDIR /var/lib/plcrun
# Modbus TCP (when [modbus] listens on it), OPC UA, the web monitor.
EXPOSE 5020 4840 8080
# Healthy while the PLC runs: the web monitor (turned on by CMD, on every
# interface of the container; reads only without its token, printed at
# start) answers /api/state with "running"; faulted or silent is unhealthy.
HEALTHCHECK --interval=30s --timeout=10s --start-period=20s CMD ["/usr/bin/plcrun", "health", "127.0.0.1:8080"]
ENTRYPOINT ["/usr/bin/plcrun", "serve"]
CMD ["/etc/plcrun/plcrun.toml", "--web", "0.0.0.0:8080"]
