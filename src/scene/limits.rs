//! The range of every number in a scene, written once: validation refuses a value outside it and
//! the editor's Left/Right steps stay inside it.

use std::fmt;

/// The values a real-number field accepts, and how far one editor step moves it.
///
/// Invariant: `min < max` and `step > 0`; at an open end the bound itself is refused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Lowest accepted value, or the bound the value must exceed when `open_min`.
    pub min: f32,
    /// Highest accepted value, or the bound the value must stay below when `open_max`.
    pub max: f32,
    /// Whether `min` itself is refused.
    pub open_min: bool,
    /// Whether `max` itself is refused.
    pub open_max: bool,
    /// How far one Left/Right press moves the value in the editor, in the field's unit.
    pub step: f32,
    /// The unit named after the range in messages ("degrees"), or "".
    pub unit: &'static str,
}

/// The values a whole-number field accepts, `min..=max`; the editor steps by one.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CountLimits {
    pub min: u32,
    pub max: u32,
}

/// Largest coordinate magnitude accepted, world units.
const FAR: f32 = 1.0e6;

/// Positions, centres, the camera's position, target and up: world units.
pub const COORDINATE: Limits = Limits::closed(-FAR, FAR, 0.1);
/// Euler angles of an object, degrees.
pub const ROTATION: Limits = Limits {
    unit: "degrees",
    ..Limits::closed(-FAR, FAR, 5.0)
};
/// Icosahedron radius, box and prism size, mesh scale: positive, world units (scale: a factor).
pub const EXTENT: Limits = Limits {
    open_min: true,
    ..Limits::closed(0.0, FAR, 0.1)
};
/// Each channel of a linear RGB colour (materials, lights, background).
pub const COLOR: Limits = Limits::closed(0.0, 1.0, 0.05);
/// The material coefficients Kd, Ks and Kr.
pub const COEFFICIENT: Limits = Limits::closed(0.0, 1.0, 0.05);
/// The Phong exponent p.
pub const SHININESS: Limits = Limits::closed(0.0, 10_000.0, 1.0);
/// Ambient intensity Ia.
pub const AMBIENT: Limits = Limits::closed(0.0, 1.0, 0.01);
/// Intensity of a point light.
pub const INTENSITY: Limits = Limits::closed(0.0, FAR, 0.05);
/// The linear (per world unit) and quadratic (per square world unit) falloff coefficients.
pub const FALLOFF: Limits = Limits::closed(0.0, FAR, 0.01);
/// Vertical field of view, degrees.
pub const FOV: Limits = Limits {
    open_min: true,
    open_max: true,
    unit: "degrees",
    ..Limits::closed(0.0, 180.0, 1.0)
};
/// World-space height of an orthographic view, world units.
pub const VIEW_HEIGHT: Limits = Limits {
    open_min: true,
    ..Limits::closed(0.0, FAR, 0.1)
};
/// Icosahedron subdivisions (8 gives 1,310,720 faces).
pub const SUBDIVISIONS: CountLimits = CountLimits { min: 0, max: 8 };
/// Segments per box or prism face edge (512 gives 3,145,728 box faces).
pub const SEGMENTS: CountLimits = CountLimits { min: 1, max: 512 };
/// Reflection recursion depth of the ray tracer (0 = no reflections).
pub const REFLECTION_DEPTH: CountLimits = CountLimits { min: 0, max: 16 };

/// Deepest reflection recursion allowed.
pub const MAX_DEPTH: u32 = REFLECTION_DEPTH.max;

impl Limits {
    /// `min..=max` with `step`, no unit.
    const fn closed(min: f32, max: f32, step: f32) -> Limits {
        Limits {
            min,
            max,
            open_min: false,
            open_max: false,
            step,
            unit: "",
        }
    }

    /// Whether `x` lies within the limits (NaN never does).
    pub fn accepts(&self, x: f32) -> bool {
        let above = if self.open_min {
            x > self.min
        } else {
            x >= self.min
        };
        let below = if self.open_max {
            x < self.max
        } else {
            x <= self.max
        };
        above && below
    }

    /// The closed range the editor's steps keep to: the accepted range, one step inside at an
    /// open end (the field of view steps from 1 to 179 degrees).
    pub fn stepping_range(&self) -> (f32, f32) {
        let lo = if self.open_min {
            self.min + self.step
        } else {
            self.min
        };
        let hi = if self.open_max {
            self.max - self.step
        } else {
            self.max
        };
        (lo, hi)
    }
}

impl CountLimits {
    /// Whether `n` lies within the limits.
    pub fn accepts(&self, n: u32) -> bool {
        (self.min..=self.max).contains(&n)
    }
}

/// A bound as written in messages: `1e6` rather than `1000000`.
struct Bound(f32);

impl fmt::Display for Bound {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.abs() >= 1.0e5 {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}

/// The range in words, as in "must be between 0 and 1".
impl fmt::Display for Limits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (min, max) = (Bound(self.min), Bound(self.max));
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        match (self.open_min, self.open_max) {
            (false, false) => write!(f, "between {min} and {max}{unit}"),
            (true, true) => write!(f, "between {min} and {max}{unit} (exclusive)"),
            (true, false) if self.min == 0.0 => {
                write!(f, "a positive finite number at most {max}{unit}")
            }
            (true, false) => write!(f, "greater than {min} and at most {max}{unit}"),
            (false, true) => write!(f, "at least {min} and less than {max}{unit}"),
        }
    }
}

/// The range in words, as in "must be between 0 and 8".
impl fmt::Display for CountLimits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "between {} and {}", self.min, self.max)
    }
}
