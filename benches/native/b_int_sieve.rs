//! Reference for `bench_b_int_sieve.st`: integer loops over an array.
//!
//! Every cycle: a full sieve of Eratosthenes up to 10 000 on
//! `flags : ARRAY[0..10000] OF BOOL` (a FOR loop to set the flags, nested
//! WHILE loops to strike multiples), then a FOR loop that counts the primes
//! and folds them into a hash modulo 65521. The loop variables `i` and `j`
//! are program variables in the ST; here they live in registers during the
//! loops and their final values are stored back, so the state after a cycle
//! is the ST's.

/// Upper bound of the sieve (and of the array index range `0..=LIMIT`).
pub const LIMIT: i32 = 10_000;

/// Program state of `bench_b_int_sieve.st`.
// Every ST variable is kept, including ones only written (`i`, `j`, `primes`, `hash`).
#[allow(dead_code)]
pub struct BenchB {
    checksum: i32,
    cycles: i32,
    flags: [bool; LIMIT as usize + 1],
    i: i32,
    j: i32,
    primes: i32,
    hash: i32,
}

impl Default for BenchB {
    fn default() -> Self {
        Self::new()
    }
}

impl BenchB {
    /// The state before the first cycle (declared initial values).
    pub fn new() -> Self {
        Self {
            checksum: 0,
            cycles: 0,
            flags: [false; LIMIT as usize + 1],
            i: 0,
            j: 0,
            primes: 0,
            hash: 0,
        }
    }

    /// Runs one scan cycle (the program uses no timers, so `now_ns` is unused).
    pub fn cycle(&mut self, now_ns: i64) {
        let s = std::hint::black_box(self);
        std::hint::black_box(now_ns);
        s.cycles = s.cycles.wrapping_add(1);

        // FOR i := 2 TO 10000 DO flags[i] := TRUE; END_FOR;
        let mut i: i32 = 2;
        while i <= LIMIT {
            s.flags[i as usize] = true;
            i += 1;
        }

        // WHILE i * i <= 10000 DO ... END_WHILE;
        let mut j = s.j;
        i = 2;
        while i.wrapping_mul(i) <= LIMIT {
            if s.flags[i as usize] {
                j = i.wrapping_mul(i);
                while j <= LIMIT {
                    s.flags[j as usize] = false;
                    j = j.wrapping_add(i);
                }
            }
            i += 1;
        }

        // Count and hash.
        let mut primes: i32 = 0;
        let mut hash: i32 = s.cycles;
        i = 2;
        while i <= LIMIT {
            if s.flags[i as usize] {
                primes = primes.wrapping_add(1);
                hash = hash.wrapping_mul(31).wrapping_add(i) % 65521;
            }
            i += 1;
        }
        // The FOR loop leaves its control variable one past the bound.
        s.i = i;
        s.j = j;
        s.primes = primes;
        s.hash = hash;
        s.checksum = primes.wrapping_mul(100_000).wrapping_add(hash);
    }

    /// The program's `checksum` variable.
    pub fn checksum(&self) -> i32 {
        self.checksum
    }
}
