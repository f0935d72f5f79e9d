//! The editor's terminal, in and out: the guard that holds raw mode and the alternate screen
//! ([`guard`]) and writes frames through [`compact_backend`]; the bytes read from it as keys and
//! replies ([`tty_input`], [`term_input`]); what the terminal can show, asked once at start-up
//! ([`color_probe`], [`graphics`]); pictures in real pixels over the cells ([`image_layer`], and the deletes written to tmux's
//! client terminal when the pane loses the focus, [`tmux_client`]); how
//! often and how cheaply frames go out over a slow link ([`pacer`], [`motion`]); and the signals
//! that end the editor ([`signals`]).

pub mod color_probe;
pub mod compact_backend;
pub mod graphics;
pub mod guard;
pub mod image_layer;
pub mod motion;
pub mod pacer;
pub mod signals;
pub mod term_input;
pub mod tmux_client;
pub mod tty_input;
