//! Compiling a verified image: every block whose instructions are all
//! supported becomes one machine-code function; the others keep a table
//! entry that runs them in the interpreter.

use super::code_memory::CodeMemory;
use super::ctx::EntryFn;
use super::report::{NativeFallback, NativeReport};
use super::{helpers, lower, support};
use crate::ir::image::Image;
use crate::ir::op::{CodeIdx, Op};
use crate::ir::verify::VerifiedImage;
use cranelift_codegen::settings::{self, Configurable};
use std::time::Instant;

/// The machine code of one image's blocks. A machine holds it beside the
/// image it was compiled from ([`Compiled::fits`]).
pub(crate) struct Compiled {
    /// One entry per block: its machine code, or [`helpers::interpret`].
    table: Box<[EntryFn]>,
    /// Which entries are machine code.
    native: Box<[bool]>,
    /// Copies of the compiled blocks' instructions: helpers receive
    /// pointers into them, which must not move while the code lives.
    _ops: Vec<Box<[Op]>>,
    /// The code itself (kept mapped while the table points into it).
    _memory: Option<CodeMemory>,
    /// Which image: the address and length of its block list.
    image_key: (usize, usize),
    report: NativeReport,
}

impl std::fmt::Debug for Compiled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Compiled")
            .field("report", &self.report)
            .finish_non_exhaustive()
    }
}

impl Compiled {
    /// The machine code of block `code`, if it was compiled.
    #[inline(always)]
    pub(crate) fn native_entry(&self, code: CodeIdx) -> Option<EntryFn> {
        match self.native.get(code.index()) {
            Some(true) => Some(self.table[code.index()]),
            _ => None,
        }
    }

    /// Whether this code was compiled from `img` (the machine runs native
    /// code only then; another image runs in the interpreter).
    #[inline]
    pub(crate) fn fits(&self, img: &Image) -> bool {
        self.image_key == key(img)
    }

    /// What was compiled and what was not.
    pub(crate) fn report(&self) -> &NativeReport {
        &self.report
    }
}

/// With `PLCRUN_NATIVE_DUMP=DIR` in the environment, the machine code of
/// each compiled block goes to `DIR/<block index>.bin` (raw bytes, e.g.
/// `objdump -D -b binary -m i386:x86-64 DIR/0.bin`) and its name to
/// `DIR/blocks.txt`: a debugging aid for reading the generated code. A
/// failed write is ignored (it changes nothing the code does).
fn dump(k: usize, name: &str, bytes: &[u8]) {
    use std::io::Write;
    let Some(dir) = std::env::var_os("PLCRUN_NATIVE_DUMP") else {
        return;
    };
    let dir = std::path::Path::new(&dir);
    let _ = std::fs::create_dir_all(dir);
    let _ = std::fs::write(dir.join(format!("{k}.bin")), bytes);
    if let Ok(mut list) = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(dir.join("blocks.txt"))
    {
        let _ = writeln!(list, "{k} {name} {} bytes", bytes.len());
    }
}

fn key(img: &Image) -> (usize, usize) {
    (img.codes.as_ptr() as usize, img.codes.len())
}

/// Compiles every block of `image` that the tier supports.
pub(crate) fn compile(image: &VerifiedImage) -> Compiled {
    let started = Instant::now();
    let img = image.image();
    let n = img.codes.len();
    let mut compiled = Compiled {
        table: vec![helpers::interpret as EntryFn; n].into_boxed_slice(),
        native: vec![false; n].into_boxed_slice(),
        _ops: Vec::new(),
        _memory: None,
        image_key: key(img),
        report: NativeReport::default(),
    };
    let isa = match host_isa() {
        Ok(isa) => isa,
        Err(why) => {
            fall_back_all(&mut compiled, img, &why);
            return compiled;
        }
    };
    let mut pieces = Vec::new();
    let mut which = Vec::new();
    for (k, block) in img.codes.iter().enumerate() {
        let reason = match support::unsupported(img, block) {
            Some(why) => why,
            None => {
                let ops: Box<[Op]> = block.ops.clone().into_boxed_slice();
                let table = compiled.table.as_ptr();
                match lower::function(&*isa, img, CodeIdx::new(k as u32), &ops, table) {
                    Ok(bytes) => {
                        dump(k, &block.name, &bytes);
                        compiled._ops.push(ops);
                        pieces.push(bytes);
                        which.push(k);
                        continue;
                    }
                    Err(why) => why,
                }
            }
        };
        compiled.report.fell_back.push(NativeFallback {
            block: block.name.clone(),
            reason,
        });
    }
    match CodeMemory::new(&pieces) {
        Ok((memory, offsets)) => {
            for (&k, &off) in which.iter().zip(&offsets) {
                // SAFETY: the bytes at `off` are a function compiled for
                // the host with the `EntryFn` signature (lower::function).
                compiled.table[k] =
                    unsafe { std::mem::transmute::<*const u8, EntryFn>(memory.at(off)) };
                compiled.native[k] = true;
                compiled.report.compiled.push(img.codes[k].name.clone());
            }
            compiled.report.code_bytes = memory.used();
            compiled._memory = Some(memory);
        }
        Err(why) => {
            for &k in &which {
                compiled.report.fell_back.push(NativeFallback {
                    block: img.codes[k].name.clone(),
                    reason: why.clone(),
                });
            }
        }
    }
    compiled.report.compile_time = started.elapsed();
    compiled
}

fn fall_back_all(compiled: &mut Compiled, img: &Image, why: &str) {
    for b in &img.codes {
        compiled.report.fell_back.push(NativeFallback {
            block: b.name.clone(),
            reason: why.to_string(),
        });
    }
}

/// The code generator for this processor, optimising for speed. Only
/// x86-64 for now: other architectures need an instruction-cache flush
/// after writing code, which `CodeMemory` does not do yet.
fn host_isa() -> Result<std::sync::Arc<dyn cranelift_codegen::isa::TargetIsa>, String> {
    if !cfg!(target_arch = "x86_64") {
        return Err("the native tier generates x86-64 code only for now".into());
    }
    let mut flags = settings::builder();
    let set = |f: &mut settings::Builder, k: &str, v: &str| {
        f.set(k, v)
            .map_err(|e| format!("cranelift setting {k}: {e}"))
    };
    set(&mut flags, "opt_level", "speed")?;
    // Cranelift's IR verifier checks the translation (a bug there would be
    // a panic, never wrong code); the tests run it, release builds spare
    // its time at every load.
    let verify = if cfg!(debug_assertions) {
        "true"
    } else {
        "false"
    };
    set(&mut flags, "enable_verifier", verify)?;
    // The code is position dependent (helper and table addresses are
    // constants in it) and never unwound through by Rust panics.
    set(&mut flags, "is_pic", "false")?;
    let builder = cranelift_native::builder().map_err(|e| format!("host ISA: {e}"))?;
    builder
        .finish(settings::Flags::new(flags))
        .map_err(|e| format!("host ISA: {e}"))
}
