//! The viewer side of the program: the offscreen picture (`shot`) and the interactive viewer
//! (`viewer` over `controller` and `viewport`), both over `render`. The `decimate` binary
//! starts them from its `viewer_start` module.

pub mod app_error;
pub mod controller;
pub mod counts;
pub mod error_map;
pub mod file_dialog;
pub mod glut;
pub mod jobs;
pub mod labels;
pub mod level_error;
pub mod lod;
pub mod menu;
pub mod menu_layout;
pub mod modal;
pub mod overlay;
pub mod panel;
pub mod popup;
pub mod save;
pub mod settle;
pub mod shot;
pub mod text_layout;
pub mod ui;
pub mod viewer;
pub mod viewport;
pub mod worker;
