//! The one list of instructions. Every instruction is declared here once,
//! with the type and the *role* of each field; the [`super::op::Op`] enum,
//! its names, and the operand visitor that relocation, the emitter, the
//! fusion pass and the verifier use ([`super::operands`]) are generated
//! from it, so an instruction cannot be added without saying what each of
//! its fields is.
//!
//! Field roles (the closed vocabulary [`super::operands::operands`] turns
//! into [`super::operands::Operand`] values):
//!
//! | role | the field is | verified |
//! |---|---|---|
//! | `Out` | a frame slot receiving the result (the emitter may retarget it) | in the frame |
//! | `Def` | a frame slot written beside other effects | in the frame |
//! | `InOut` | a frame slot read and written (accumulator, loop variable) | in the frame |
//! | `In` | a frame slot read (a value, a pointer, a string id) | in the frame |
//! | `Run(n)` | the first of `n` consecutive slots read (`n` another field or a literal) | the whole run in the frame |
//! | `FbInstance(code)` | the frame slot where an instance of user FB `code` starts | the callee's frame in this frame |
//! | `NativeInstance(fb)` | the frame slot where a native FB instance starts | its pins in this frame |
//! | `Target` | a jump target (instruction index, patched by the emitter) | in the block, not an operand word |
//! | `ShortTarget` | a 16-bit jump target written once | as `Target` |
//! | `Const` | an index into `Image::consts` | in the table |
//! | `StrConst` | an index into `Image::str_consts` | in the table |
//! | `Array(use)` | an index into `Image::arrays`, used as `ArrayUse::use` says | in the table, the extent `use` needs |
//! | `ScalarType` | an index into `Image::scalar_types` | in the table |
//! | `Code(kind)` | a code-block index of the given `CodeKind` | in the table, of that kind |
//! | `Chart` | an index into `Image::charts` | in the table (the chart is verified on its own) |
//! | `Host` | an index into `Image::hosts` | in the table |
//! | `Abs` | an absolute memory address | inside memory |
//! | `Data` | an immediate, a shift, a predicate, a static offset | nothing to check |
//!
//! Field types are single names. Every role but `Data` and `Abs` takes
//! one typed index ([`super::index`]): a slot role a `Slot`, `Target` a
//! `Target`, `ShortTarget` a `ShortTarget`, `Const` a `ConstIdx`,
//! `StrConst` a `StrConstIdx`, `Array` an `ArrayIdx` or `ShortArrayIdx`,
//! `ScalarType` a `ScalarTypeIdx`, `Code` a `CodeIdx`, `Chart` a
//! `ChartIdx`, `Host` a `HostIdx`; and no typed index may be declared `Data`. A mismatch
//! either way does not compile.
//!
//! After the fields an instruction may name its *shape* (how it relates to
//! its neighbours; [`super::operands::Shape`]): `@ TakesOperandWord` (the
//! next instruction is its `Operand` word), `@ OperandWord` (it is such a
//! word), `@ Fused(check)` (a loop superinstruction whose partner `check`
//! verifies). Without one the instruction stands alone.

/// Calls macro `$m` with the whole instruction list.
macro_rules! for_each_op {
    ($m:ident) => {
        $m! {
            /// No operation (left where an instruction was removed).
            Nop;
            /// `d := constants[k]`.
            LoadK { d: Slot => Out, k: ConstIdx => Const };
            /// `d := imm` (sign-extended 32-bit immediate).
            LoadI { d: Slot => Out, imm: i32 => Data };
            /// `d := s`.
            Mov { d: Slot => Out, s: Slot => In };
            /// `d := mem[abs]`.
            LoadAbs { d: Slot => Out, abs: u32 => Abs };
            /// `mem[abs] := s`.
            StoreAbs { abs: u32 => Abs, s: Slot => In };
            /// `d := mem[mem[p] + off]`.
            LoadInd { d: Slot => Out, p: Slot => In, off: u32 => Data };
            /// `mem[mem[p] + off] := s`.
            StoreInd { p: Slot => In, off: u32 => Data, s: Slot => In };
            /// `d := base + off` (absolute address of a frame slot).
            AddrOf { d: Slot => Def, off: Slot => In };
            /// `d := mem[p] + off` (address arithmetic on a pointer).
            AddrAdd { d: Slot => Def, p: Slot => In, off: u32 => Data };
            /// Checked 1-D element load: `d := frame[arr + (idx - lo) * stride]` using array descriptor `desc`.
            LoadElem { d: Slot => Out, idx: Slot => In, desc: ArrayIdx => Array(Elems) };
            /// Checked 1-D element store.
            StoreElem { idx: Slot => In, s: Slot => In, desc: ArrayIdx => Array(Elems) };
            /// Element address: `d := d + offset + checked(idx - lo) * stride` where
            /// `d` holds the array's absolute address on entry (descriptor `desc`).
            ElemAddr { d: Slot => InOut, idx: Slot => In, desc: ArrayIdx => Array(Any) };
            /// Element address in the current frame:
            /// `d := base + offset + checked(idx - lo) * stride` (descriptor `desc`).
            ElemRef { d: Slot => Def, idx: Slot => In, desc: ArrayIdx => Array(Span) };
            /// Linearised multi-dimensional index step: `acc := acc * len + checked(idx - lo)`.
            IndexStep { acc: Slot => InOut, idx: Slot => In, desc: ArrayIdx => Array(Any) };
            /// The same step against bounds held in slots (an `ARRAY[*]`
            /// parameter's), `lo` in `bounds` and `hi` after it:
            /// `acc := acc * (hi - lo + 1) + checked(idx - lo)`.
            OpenIndexStep { acc: Slot => InOut, idx: Slot => In, bounds: Slot => Run(2) };

            /// Signed add wrapped at `64 - shift` bits.
            AddS { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Unsigned add wrapped at `64 - shift` bits.
            AddU { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Signed add of an immediate.
            AddSI { d: Slot => Out, a: Slot => In, imm: i32 => Data, shift: u8 => Data };
            /// Signed subtract.
            SubS { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Unsigned subtract.
            SubU { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Signed multiply.
            MulS { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Unsigned multiply.
            MulU { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Signed divide (truncating); faults on zero.
            DivS { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Unsigned divide; faults on zero.
            DivU { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Signed MOD (sign of the dividend); faults on zero.
            ModS { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Unsigned MOD; faults on zero.
            ModU { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Signed MOD by a non-zero immediate.
            ModSI { d: Slot => Out, a: Slot => In, imm: i32 => Data, shift: u8 => Data };
            /// Signed negation.
            NegS { d: Slot => Out, a: Slot => In, shift: u8 => Data };
            /// Integer power `a ** b` (b >= 0), wrapping.
            PowS { d: Slot => Out, a: Slot => In, b: Slot => In, shift: u8 => Data };
            /// Signed ABS, wrapping.
            AbsS { d: Slot => Out, a: Slot => In, shift: u8 => Data };

            /// REAL add.
            AddF32 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// REAL subtract.
            SubF32 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// REAL multiply.
            MulF32 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// REAL divide (IEEE: x/0 gives an infinity or NaN).
            DivF32 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// REAL negation.
            NegF32 { d: Slot => Out, a: Slot => In };
            /// REAL power.
            PowF32 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// REAL math function.
            MathF32 { d: Slot => Out, a: Slot => In, f: MathFn => Data };
            /// LREAL add.
            AddF64 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// LREAL subtract.
            SubF64 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// LREAL multiply.
            MulF64 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// LREAL divide.
            DivF64 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// LREAL negation.
            NegF64 { d: Slot => Out, a: Slot => In };
            /// LREAL power.
            PowF64 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// LREAL math function.
            MathF64 { d: Slot => Out, a: Slot => In, f: MathFn => Data };

            /// Bitwise AND (also BOOL AND).
            And { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// Bitwise OR.
            Or { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// Bitwise XOR.
            Xor { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// BOOL NOT.
            NotB { d: Slot => Out, a: Slot => In };
            /// Bit-string NOT masked to `64 - shift` bits.
            NotW { d: Slot => Out, a: Slot => In, shift: u8 => Data };
            /// `d := a AND NOT b` (BOOL).
            AndN { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// `d := a OR NOT b` (BOOL).
            OrN { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// Shifts/rotations of a `bits`-wide bit string by `n` (slot `b`).
            Shift { d: Slot => Out, a: Slot => In, b: Slot => In, kind: ShiftKind => Data, bits: u8 => Data };

            /// Signed comparison (also for unsigned up to 32 bits, TIME, dates).
            CmpS { d: Slot => Out, a: Slot => In, b: Slot => In, cmp: Cmp => Data };
            /// Unsigned 64-bit comparison.
            CmpU { d: Slot => Out, a: Slot => In, b: Slot => In, cmp: Cmp => Data };
            /// REAL comparison.
            CmpF32 { d: Slot => Out, a: Slot => In, b: Slot => In, cmp: Cmp => Data };
            /// LREAL comparison.
            CmpF64 { d: Slot => Out, a: Slot => In, b: Slot => In, cmp: Cmp => Data };
            /// Signed comparison with an immediate.
            CmpSI { d: Slot => Out, a: Slot => In, imm: i32 => Data, cmp: Cmp => Data };
            /// String comparison.
            CmpStr { d: Slot => Out, a: Slot => In, b: Slot => In, cmp: Cmp => Data };

            /// Conversion.
            Convert { d: Slot => Out, a: Slot => In, conv: Conv => Data };
            /// `d := a * b + c` on REAL (each operation rounded as written, no
            /// fused rounding); `c` is in the `Operand` word that follows.
            MulAddF32 { d: Slot => Out, a: Slot => In, b: Slot => In } @ TakesOperandWord;
            /// `d := a * b + c` on LREAL; `c` is in the following `Operand` word.
            MulAddF64 { d: Slot => Out, a: Slot => In, b: Slot => In } @ TakesOperandWord;
            /// The extra operand of the instruction before it (never executed on
            /// its own: the instruction before it consumes it).
            Operand { s: Slot => In } @ OperandWord;
            /// Conditional move: `if c { d := s }` (SEL).
            CMov { d: Slot => Out, c: Slot => In, s: Slot => In };
            /// Signed MIN/MAX: `d := if (a < b) == min { a } else { b }`.
            MinMaxS { d: Slot => Out, a: Slot => In, b: Slot => In, max: bool => Data };
            /// Unsigned 64-bit MIN/MAX.
            MinMaxU { d: Slot => Out, a: Slot => In, b: Slot => In, max: bool => Data };
            /// REAL MIN/MAX.
            MinMaxF32 { d: Slot => Out, a: Slot => In, b: Slot => In, max: bool => Data };
            /// LREAL MIN/MAX.
            MinMaxF64 { d: Slot => Out, a: Slot => In, b: Slot => In, max: bool => Data };
            /// MUX: `d := slots[first + k]` for k = value of `k`, faulting if `k >= n`.
            Mux { d: Slot => Out, k: Slot => In, first: Slot => Run(n), n: u16 => Data };
            /// Duration times REAL/LREAL factor (TIME * REAL), rounding to ns.
            MulTimeF64 { d: Slot => Out, a: Slot => In, b: Slot => In };
            /// Duration divided by LREAL.
            DivTimeF64 { d: Slot => Out, a: Slot => In, b: Slot => In };

            /// String copy (truncated to the destination's capacity); `d` and
            /// `s` hold string ids.
            StrMov { d: Slot => In, s: Slot => In };
            /// String function, arguments in consecutive slots from `a` (the
            /// result slot `d` holds a string id, or receives LEN/FIND's integer).
            StrCall { d: Slot => InOut, a: Slot => Run(4), f: StrFn => Data };
            /// Set string `d` (a slot holding its id) to the constant string `k`.
            StrConst { d: Slot => In, k: StrConstIdx => StrConst };
            /// Convert a scalar of type `ty` (index into the type list) to its literal text.
            ToStr { d: Slot => In, a: Slot => In, ty: ScalarTypeIdx => ScalarType };
            /// Parse string `a` as a value of type `ty`.
            FromStr { d: Slot => Def, a: Slot => In, ty: ScalarTypeIdx => ScalarType };

            /// Unconditional jump.
            Jmp { t: Target => Target };
            /// Jump if the BOOL slot is FALSE.
            Jz { c: Slot => In, t: Target => Target };
            /// Jump if the BOOL slot is TRUE.
            Jnz { c: Slot => In, t: Target => Target };
            /// Jump if `a cmp imm` is FALSE (fused compare and branch on signed values).
            JnCmpSI { a: Slot => In, imm: i32 => Data, cmp: Cmp => Data, t: Target => Target };
            /// Jump if `a cmp b` is FALSE (signed).
            JnCmpS { a: Slot => In, b: Slot => In, cmp: Cmp => Data, t: Target => Target };

            /// Array fill (`FOR i := start TO lim DO arr[i] := v; END_FOR` with
            /// `i` already set to start): when every index is inside the array and
            /// `lim + 1` fits the type, stores `v` in all elements and sets
            /// `i := lim + 1`; otherwise does nothing (the loop that follows runs as
            /// written and faults where it would).
            FillElems { i: Slot => InOut, v: Slot => In, lim: i32 => Data, desc: ShortArrayIdx => Array(Dense), shift: u8 => Data };
            /// Jump if the BOOL array element `frame[desc][idx]` is FALSE (checked index).
            JzElem { idx: Slot => In, desc: ArrayIdx => Array(Elems), t: Target => Target };
            /// Jump if the BOOL array element is TRUE.
            JnzElem { idx: Slot => In, desc: ArrayIdx => Array(Elems), t: Target => Target };
            /// `d := d + b` (signed, wrapped), then jump to `t` if `d cmp imm`
            /// (a WHILE loop stepping its variable just before its test).
            AddBr { d: Slot => InOut, b: Slot => In, imm: i16 => Data, t: ShortTarget => ShortTarget, cmp: Cmp => Data, shift: u8 => Data };
            /// Jump if `a cmp b` is FALSE on REAL values (NaN compares FALSE, so it jumps).
            JnCmpF32 { a: Slot => In, b: Slot => In, cmp: Cmp => Data, t: Target => Target };
            /// Jump if `a cmp b` is FALSE on LREAL values.
            JnCmpF64 { a: Slot => In, b: Slot => In, cmp: Cmp => Data, t: Target => Target };
            /// FOR back edge: `i := i + step`, then jump to `t` while
            /// `i <= lim` (`step > 0`) or `i >= lim` (`step < 0`). The test uses the
            /// exact sum, so a loop up to its type's largest value ends.
            ForNext { i: Slot => InOut, lim: i32 => Data, t: Target => Target, step: i16 => Data, shift: u8 => Data };
            /// As `ForNext` with the limit in a slot.
            ForNextS { i: Slot => InOut, lim: Slot => In, t: Target => Target, step: i16 => Data, shift: u8 => Data };

            /// `d := frame[idx + bias]`: an element of a one-slot-per-element frame
            /// array whose index the compiler proved in range (the control
            /// variable of an enclosing FOR loop over a constant range inside the
            /// array bounds, never written in the loop body). The array check is
            /// gone; the executor still keeps the access inside the frame.
            LoadElemU { d: Slot => Out, idx: Slot => In, bias: i32 => Data };
            /// `frame[idx + bias] := s`, proved in range as for `LoadElemU`.
            StoreElemU { idx: Slot => In, s: Slot => In, bias: i32 => Data };
            /// Loop superinstruction: a `StoreElem` whose next instruction is an
            /// `AddBr` stepping `idx` and jumping back here (a WHILE loop whose
            /// body is one element store, such as striking multiples in a sieve).
            /// Runs the pair until the `AddBr` test fails, then continues after
            /// it, in one dispatch; the `AddBr` stays in place as the second word.
            StoreStep { idx: Slot => InOut, s: Slot => In, desc: ArrayIdx => Array(Elems) } @ Fused(crate::ir::fuse::store_step_partner);
            /// Loop superinstruction: a `ForNext` whose target `t` is a
            /// `JzElem` (`when` TRUE) or `JnzElem` (`when` FALSE) on `i` that jumps
            /// back here (a FOR loop whose body is guarded by `IF arr[i] THEN`).
            /// Steps `i` over every iteration the element test would skip, then
            /// continues at `t + 1` (the body), at `t` (the index is out of range:
            /// the test faults there) or after the loop.
            ForScan { i: Slot => InOut, lim: i32 => Data, t: ShortTarget => ShortTarget, desc: ShortArrayIdx => Array(Elems), step: i8 => Data, shift: u8 => Data, when: bool => Data } @ Fused(crate::ir::fuse::for_scan_partner);

            /// Call a user FB body (code block `code`) on the instance at frame slot `inst`.
            CallFb { code: CodeIdx => Code(FunctionBlock), inst: Slot => FbInstance(code) };
            /// Call a user FB on the instance whose absolute address is in slot `p`.
            CallFbInd { code: CodeIdx => Code(FunctionBlock), p: Slot => In };
            /// Call a native FB on the instance at frame slot `inst`.
            CallNative { fb: NativeFb => Data, inst: Slot => NativeInstance(fb) };
            /// Call a native FB on the instance whose address is in slot `p`.
            CallNativeInd { fb: NativeFb => Data, p: Slot => In };
            /// Call a function: reset its static frame, run its code at its frame base.
            CallFn { code: CodeIdx => Code(Function) };
            /// Copies `n` slots from address `mem[s]` to address `mem[d]` (aggregates by value).
            MemCopy { d: Slot => In, s: Slot => In, n: u32 => Data };
            /// `d := current clock value` (PLC_CLOCK).
            Clock { d: Slot => Out };
            /// Return from the current code block.
            Ret;
            /// One call of the SFC chart `chart` (index into `Image::charts`) on
            /// the current instance: evolution, then action control.
            Sfc { chart: ChartIdx => Chart };
            /// The body of a FUNCTION or FUNCTION_BLOCK the host registered
            /// (entry `id` of `Image::hosts`): runs the host's code on the
            /// current frame (the FB instance or the function's frame).
            CallHost { id: HostIdx => Host };

            // --- refs: references and pointers (`crate::ir::refs`) ---
            /// `d := a reference to the object of `len` slots at the absolute
            /// address in `p`` (`REF(x)`, `ADR(x)`): the machine numbers the object.
            /// `layout` is the code (`ir::refs::elem_code`) of the object's
            /// elementary type, or of its aggregate's byte layout
            /// (`ir::refs::FIRST_AGGREGATE_LAYOUT`), which gives its bytes to
            /// byte views (0: none).
            RefMake { d: Slot => Out, p: Slot => In, len: u32 => Data, layout: u16 => Data };
            /// `d := the absolute address of the `width` slots reference `r`
            /// designates`; faults on NULL (R030), outside its object (R031) or
            /// an object of an earlier memory layout (R032).
            RefAddr { d: Slot => Out, r: Slot => In, width: u32 => Data };
            /// `d := reference `d` moved to element `idx` of the array `desc`
            /// describes` (bounds checked against the declared array; the
            /// dereference that follows checks the object); a byte view moves by
            /// `unit` bytes per element.
            RefIndex { d: Slot => InOut, idx: Slot => In, desc: ArrayIdx => Array(Any), unit: u16 => Data };
            /// `d := pointer `d` moved by `b` bytes`: `b / unit` elements of
            /// `slots` slots each; a `b` that is not a multiple of `unit` makes a
            /// pointer that faults when dereferenced.
            PtrAdd { d: Slot => InOut, b: Slot => In, unit: u16 => Data, slots: u16 => Data };
            /// `d := TRUE if `r` designates `width` slots inside a live object`
            /// (`__ISVALIDREF`).
            RefValid { d: Slot => Out, r: Slot => In, width: u32 => Data };
            /// A call through an interface variable that holds no instance
            /// (no implementing type matched its type id): fault R080.
            FaultNullItf;
            /// A method entered on an instance where it is already running (a
            /// cycle of calls through interfaces came back to it): fault R081.
            FaultReentry;
            /// `F_RaiseException(c)` (Tc2_System): an exception with the code
            /// in `c` (a `__SYSTEM.ExceptionCode` number), fault R082.
            FaultRaise { c: Slot => In };
            /// `d := the value of type `elem` (`ir::refs::elem_code`) pointer `r`
            /// designates`: a slot of its object, or the object's bytes for a
            /// byte view (`ir::refs::VIEW`); faults as `RefAddr` does.
            RefLoad { d: Slot => Out, r: Slot => In, elem: u8 => Data };
            /// `the value of type `elem` pointer `r` designates := s` (a slot of
            /// its object, or its bytes for a byte view).
            RefStore { r: Slot => In, s: Slot => In, elem: u8 => Data };
            /// `d := pointer `d` as a byte view` (`POINTER TO BYTE := ADR(str)`):
            /// a typed pointer's offset becomes `unit` bytes per slot.
            RefView { d: Slot => InOut, unit: u16 => Data };
            /// `d := the integer image of pointer `d`` (`dw := pt`, `pt < end`):
            /// object number and byte offset (`ir::refs::IMAGE_OFFSET_BITS`);
            /// a typed pointer's offset counts `unit` bytes per slot.
            PtrToInt { d: Slot => InOut, unit: u16 => Data };
            /// `d := the pointer whose integer image is `d`` (`pt := dw`): a byte
            /// view of the object the image names (0 is `NULL`); when `ty` is
            /// a type (not [`crate::ir::refs::NO_TYPE`]) and the memory there
            /// holds a value of it, a typed pointer to that value instead
            /// (`vm::type_at`).
            IntToPtr { d: Slot => InOut, ty: u32 => Data };
        }
    };
}

pub(crate) use for_each_op;
