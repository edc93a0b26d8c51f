//! The CHARIOT plant: a cart on a track between station A (position 0) and
//! station B, driven by two contactors (KMAV forward, KMAR backward), with a
//! limit switch at each station and an end stop a little past each; and
//! the operator who presses the start button when the cart is at A.
//!
//! Whole millimetres and whole cycles: the simulation is exact and the
//! same on every machine.

use std::fmt;

/// The cart and its track.
#[derive(Debug, Clone, PartialEq)]
pub struct Cart {
    /// Distance from station A, in millimetres.
    pub position_mm: i64,
    /// Where station B's limit switch closes.
    pub track_mm: i64,
    /// Distance covered in one cycle with a contactor closed.
    pub step_mm: i64,
    /// How far past a limit switch the end stops are.
    pub overtravel_mm: i64,
}

/// The plant was driven into a state a real one cannot survive.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PlantError {
    /// KMAV and KMAR closed together: a short circuit across the motor.
    BothContactors {
        /// The cycle it happened in.
        cycle: u64,
    },
    /// The cart was driven into an end stop.
    EndStop {
        /// The cycle it happened in.
        cycle: u64,
        /// Where the cart would have been.
        position_mm: i64,
    },
}

impl fmt::Display for PlantError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlantError::BothContactors { cycle } => {
                write!(f, "cycle {cycle}: KMAV and KMAR are both closed")
            }
            PlantError::EndStop { cycle, position_mm } => {
                write!(
                    f,
                    "cycle {cycle}: the cart hit an end stop at {position_mm} mm"
                )
            }
        }
    }
}

impl std::error::Error for PlantError {}

impl Cart {
    /// A cart standing at A on a 1.5 m track, 1 m/s with 10 ms cycles.
    pub fn new() -> Cart {
        Cart {
            position_mm: 0,
            track_mm: 1500,
            step_mm: 10,
            overtravel_mm: 50,
        }
    }

    /// Limit switch A (FcA): closed at or behind station A.
    pub fn at_a(&self) -> bool {
        self.position_mm <= 0
    }

    /// Limit switch B (FcB): closed at or past station B.
    pub fn at_b(&self) -> bool {
        self.position_mm >= self.track_mm
    }

    /// Moves the cart for one cycle with the contactors as the PLC left
    /// them.
    pub fn advance(&mut self, cycle: u64, kmav: bool, kmar: bool) -> Result<(), PlantError> {
        let next = match (kmav, kmar) {
            (true, true) => return Err(PlantError::BothContactors { cycle }),
            (true, false) => self.position_mm + self.step_mm,
            (false, true) => self.position_mm - self.step_mm,
            (false, false) => self.position_mm,
        };
        if next > self.track_mm + self.overtravel_mm || next < -self.overtravel_mm {
            return Err(PlantError::EndStop {
                cycle,
                position_mm: next,
            });
        }
        self.position_mm = next;
        Ok(())
    }
}

impl Default for Cart {
    fn default() -> Cart {
        Cart::new()
    }
}

/// The operator: once the "at origin" lamp (VOM) has been lit for
/// `wait_cycles` (loading), presses the start button (Dcy) for
/// `press_cycles`, then waits for the lamp to go out and come back.
#[derive(Debug, Clone, PartialEq)]
pub struct Operator {
    /// Loading time, in cycles.
    pub wait_cycles: u32,
    /// How long the button is held, in cycles.
    pub press_cycles: u32,
    lit_for: u32,
}

impl Operator {
    /// Loads for 0.5 s and presses for 0.1 s (10 ms cycles).
    pub fn new() -> Operator {
        Operator {
            wait_cycles: 50,
            press_cycles: 10,
            lit_for: 0,
        }
    }

    /// The button for this cycle, given the lamp as the last cycle left it.
    pub fn button(&mut self, lamp: bool) -> bool {
        self.lit_for = if lamp { self.lit_for + 1 } else { 0 };
        (self.wait_cycles..self.wait_cycles + self.press_cycles).contains(&self.lit_for)
    }
}

impl Default for Operator {
    fn default() -> Operator {
        Operator::new()
    }
}
