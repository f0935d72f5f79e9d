//! Which overlays a render draws.

use std::str::FromStr;

/// The overlays to draw, and what is selected. All off by default: a render without overlays
/// runs no overlay code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Overlays {
    /// A ground grid under the scene.
    pub grid: bool,
    /// The axis gizmo in the bottom-left corner.
    pub axes: bool,
    /// The bounding box of the selection, or of the scene.
    pub bbox: bool,
    /// An outline around the selection, or around every object.
    pub outline: bool,
    /// The selected world objects, `first..end`; `None` is the whole scene.
    pub selected: Option<(u32, u32)>,
    /// With `bbox`: its lengths written as text beside its edges, in frames at least
    /// [`super::dimensions::MIN_HEIGHT`] pixels high. On for `--overlay bbox`, off in the
    /// editor's preview, whose status line gives them.
    pub labels: bool,
}

impl Overlays {
    /// Whether any overlay is drawn.
    pub fn any(&self) -> bool {
        self.grid || self.axes || self.bbox || self.outline
    }

    /// Whether world object `object` is selected (every object is, without a selection).
    pub fn is_selected(selected: Option<(u32, u32)>, object: u32) -> bool {
        selected.is_none_or(|(first, end)| (first..end).contains(&object))
    }

    /// The names of the overlays drawn, comma-separated, as `--overlay` takes them.
    pub fn names(&self) -> String {
        let on = [
            (self.grid, "grid"),
            (self.axes, "axes"),
            (self.bbox, "bbox"),
            (self.outline, "outline"),
        ];
        let names: Vec<&str> = on.iter().filter(|(o, _)| *o).map(|(_, n)| *n).collect();
        names.join(",")
    }
}

/// One overlay, as a key toggles it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OverlayKind {
    Grid,
    Axes,
    Bbox,
    Outline,
}

impl Overlays {
    /// Turns `kind` on when it is off, off when it is on.
    pub fn toggle(&mut self, kind: OverlayKind) {
        let flag = match kind {
            OverlayKind::Grid => &mut self.grid,
            OverlayKind::Axes => &mut self.axes,
            OverlayKind::Bbox => &mut self.bbox,
            OverlayKind::Outline => &mut self.outline,
        };
        *flag = !*flag;
    }
}

/// A name in an overlay list that is not an overlay.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("`{0}` is not an overlay: use grid, axes, bbox or outline, comma-separated")]
pub struct UnknownOverlay(pub String);

impl FromStr for Overlays {
    type Err = UnknownOverlay;

    /// A comma-separated list such as `grid,axes,bbox`.
    fn from_str(list: &str) -> Result<Overlays, UnknownOverlay> {
        let mut overlays = Overlays::default();
        for name in list.split(',').map(str::trim).filter(|n| !n.is_empty()) {
            let flag = match name {
                "grid" => &mut overlays.grid,
                "axes" => &mut overlays.axes,
                "bbox" => &mut overlays.bbox,
                "outline" => &mut overlays.outline,
                _ => return Err(UnknownOverlay(name.to_string())),
            };
            *flag = true;
        }
        overlays.labels = overlays.bbox;
        Ok(overlays)
    }
}

#[cfg(test)]
mod tests {
    use super::Overlays;

    #[test]
    fn a_list_turns_on_its_overlays_and_reads_back() {
        let overlays: Overlays = "grid, bbox".parse().expect("valid list");
        assert!(overlays.grid && overlays.bbox && !overlays.axes && !overlays.outline);
        assert_eq!(overlays.names(), "grid,bbox");
        assert!("grid,ruler".parse::<Overlays>().is_err());
        assert!(!"".parse::<Overlays>().expect("empty list").any());
    }
}
