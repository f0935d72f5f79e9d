//! The editor and the disk, in the background: unsaved edits kept in the [`recovery`] file by
//! [`autosave`], the scene and its model files watched for live reload ([`disk_watch`]), and
//! exports rendered to a file on their own thread ([`export_job`]).

pub mod autosave;
pub mod disk_watch;
pub mod export_job;
pub mod recovery;
