//! One set of limits serves validation and the editor: stepping a property as far as it goes
//! lands on a value validation accepts, one more step is refused, and just past that value
//! validation refuses too (so the editor reaches the edge of what a file may hold).

use rastray::scene::{Scene, from_toml_str, validate};
use rastray::tui::state::fields::{Key, Part, Range, Value, stepped, typed};
use rastray::tui::state::selection::Item;

/// Every item kind, with a camera whose position and target lie far apart across the view: no
/// coordinate bound of one can make the view vertical (a different rule, checked elsewhere).
const SCENE: &str = r#"
[camera]
position = [-900000.0, 0.0, -900000.0]
target = [900000.0, 0.0, 900000.0]
[[light]]
position = [1.0, 2.0, 3.0]
[[object]]
type = "icosahedron"
radius = 1.0
[[object]]
type = "box"
size = [1.0, 2.0, 3.0]
[[object]]
type = "prism"
size = [1.0, 2.0, 3.0]
[[object]]
type = "mesh"
path = "tests/data/suzanne.obj"
"#;

fn scene() -> Scene {
    from_toml_str(SCENE, std::path::Path::new("limits.toml")).expect("a valid scene")
}

/// Every numeric property of every item, with its range.
fn numeric_properties(scene: &Scene) -> Vec<(Item, Key, Range)> {
    let items = std::iter::once(Item::Settings)
        .chain((0..scene.lights.len()).map(Item::Light))
        .chain((0..scene.objects.len()).map(Item::Object));
    let mut found = Vec::new();
    for item in items {
        let part = Part::of(scene, item).expect("the item exists");
        for key in part.keys() {
            let numeric = matches!(part.value(key), Some(Value::Number(_) | Value::Count(_)));
            match key.range() {
                Some(range) => {
                    assert!(numeric, "{key:?} has a range but no number");
                    found.push((item, key, range));
                }
                None => assert!(!numeric, "{key:?} is a number without a range"),
            }
        }
    }
    found
}

fn number(scene: &Scene, item: Item, key: Key) -> f64 {
    match Part::of(scene, item).and_then(|p| p.value(key)) {
        Some(Value::Number(x)) => x as f64,
        Some(Value::Count(n)) => n as f64,
        other => panic!("{key:?} is not a number: {other:?}"),
    }
}

/// The float next to finite `x`: above it when `up`, else below.
fn just_past(x: f32, up: bool) -> f32 {
    if x == 0.0 {
        let tiny = f32::from_bits(1);
        return if up { tiny } else { -tiny };
    }
    // Away from zero the magnitude grows by one unit in the last place.
    let away = up == (x > 0.0);
    f32::from_bits(if away {
        x.to_bits() + 1
    } else {
        x.to_bits() - 1
    })
}

#[test]
fn stepping_reaches_each_bound_validation_accepts_and_no_further() {
    let start = scene();
    let properties = numeric_properties(&start);
    assert!(properties.len() > 40, "{} properties", properties.len());
    for (item, key, range) in properties {
        for up in [true, false] {
            let next = if up { 1 } else { -1 };
            // One step back first, in case the value starts at the bound (a value at the other
            // bound cannot step back, and needs not).
            let from = stepped(&start, item, key, -next).unwrap_or_else(|_| start.clone());
            let at_bound = stepped(&from, item, key, 1_000_000_000 * next)
                .unwrap_or_else(|e| panic!("{key:?} up={up}: stepping to the bound refused: {e}"));
            assert!(validate(&at_bound).is_ok());
            let value = number(&at_bound, item, key);
            assert!(
                stepped(&at_bound, item, key, next).is_err(),
                "{key:?} stepped past {value}"
            );
            match range {
                Range::Number(limits) => {
                    let (lo, hi) = limits.stepping_range();
                    let (bound, open) = if up {
                        (limits.max, limits.open_max)
                    } else {
                        (limits.min, limits.open_min)
                    };
                    assert_eq!(value as f32, if up { hi } else { lo }, "{key:?}");
                    assert!(limits.accepts(value as f32), "{key:?} {value}");
                    // Validation draws its line exactly where the limits do.
                    let refused = if open { bound } else { just_past(bound, up) };
                    assert!(
                        typed(&start, item, key, &refused.to_string()).is_err(),
                        "{key:?}: validation accepts {refused}"
                    );
                    if open {
                        let inside = just_past(bound, !up);
                        assert!(
                            typed(&start, item, key, &inside.to_string()).is_ok(),
                            "{key:?}: validation refuses {inside}"
                        );
                    }
                }
                Range::Count(limits) => {
                    let bound = if up { limits.max } else { limits.min };
                    assert_eq!(value, bound as f64, "{key:?}");
                    let past = if up {
                        bound as i64 + 1
                    } else {
                        bound as i64 - 1
                    };
                    assert!(
                        typed(&start, item, key, &past.to_string()).is_err(),
                        "{key:?}: validation accepts {past}"
                    );
                }
            }
        }
    }
}

#[test]
fn a_step_never_moves_against_its_direction() {
    // A radius typed below the smallest step stays put when stepped down, instead of jumping up
    // to the stepping range.
    let start = scene();
    let item = Item::Object(0);
    let tiny = typed(&start, item, Key::Radius, "0.001").expect("validation accepts 0.001");
    let refusal = stepped(&tiny, item, Key::Radius, -1).expect_err("already below the range");
    assert!(refusal.contains("limit"), "{refusal}");
    let up = stepped(&tiny, item, Key::Radius, 1).expect("a step up");
    assert!(number(&up, item, Key::Radius) > 0.001);
}
