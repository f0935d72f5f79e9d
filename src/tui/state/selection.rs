//! Where the user is: the focused pane, the chosen scene-list entry and the chosen property.

/// One entry of the scene list.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Item {
    /// Camera, ambient light, background and recursion depth.
    Settings,
    /// Index into `scene.lights`.
    Light(usize),
    /// Index into `scene.objects`.
    Object(usize),
}

/// The pane that receives navigation keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Focus {
    #[default]
    List,
    Properties,
    Preview,
}

impl Focus {
    /// The next pane (Tab).
    pub fn next(self) -> Focus {
        match self {
            Focus::List => Focus::Properties,
            Focus::Properties => Focus::Preview,
            Focus::Preview => Focus::List,
        }
    }

    /// The previous pane (Shift-Tab).
    pub fn prev(self) -> Focus {
        self.next().next()
    }
}

/// `i` moved one place up or down in a list of `n`, wrapping around; 0 in an empty list.
pub fn wrap_step(i: usize, n: usize, down: bool) -> usize {
    match (n, down) {
        (0, _) => 0,
        (_, true) => (i + 1) % n,
        (_, false) => (i + n - 1) % n,
    }
}

/// The focused pane, and indices into the scene list and into the chosen item's properties.
/// Indices may go stale when the scene changes; [`Selection::clamp_item`] and
/// [`Selection::clamp_field`] bring them back.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Selection {
    focus: Focus,
    item: usize,
    field: usize,
}

impl Selection {
    /// The pane that receives navigation keys.
    pub fn focus(&self) -> Focus {
        self.focus
    }

    /// Index into the scene list.
    pub fn item(&self) -> usize {
        self.item
    }

    /// Index into the chosen item's properties.
    pub fn field(&self) -> usize {
        self.field
    }

    /// Gives the keys to `focus`.
    pub fn focus_on(&mut self, focus: Focus) {
        self.focus = focus;
    }

    /// Chooses entry `item` of the scene list, and its first property.
    pub fn choose_item(&mut self, item: usize) {
        self.item = item;
        self.field = 0;
    }

    /// Moves one entry up or down a scene list of `items` entries, wrapping around.
    pub fn step_item(&mut self, items: usize, down: bool) {
        self.choose_item(wrap_step(self.item, items, down));
    }

    /// Moves one property up or down a list of `fields` properties, wrapping around.
    pub fn step_field(&mut self, fields: usize, down: bool) {
        self.field = wrap_step(self.field, fields, down);
    }

    /// Keeps the item index inside a scene list of `items` entries.
    pub fn clamp_item(&mut self, items: usize) {
        self.item = self.item.min(items.saturating_sub(1));
    }

    /// Keeps the property index inside a list of `fields` properties.
    pub fn clamp_field(&mut self, fields: usize) {
        self.field = self.field.min(fields.saturating_sub(1));
    }
}
