//! Scenes named by a study: a built-in scene's name, or the path of a model file
//! (`scene = "models/heavy-top.toml"` in a sweep or hard-case file), relative to the directory
//! of the file that names it.

use std::path::{Path, PathBuf};

use tumble_scenarios::{Scene, SceneError, scenes};

/// Whether `name` names a model file rather than a built-in scene (it ends in `.toml`).
#[must_use]
pub fn names_a_file(name: &str) -> bool {
    Path::new(name)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("toml"))
}

/// The path of `name` as written in the file `origin`: relative to `origin`'s directory.
#[must_use]
pub fn relative_to(name: &str, origin: &str) -> PathBuf {
    let path = Path::new(name);
    if path.is_absolute() {
        return path.to_path_buf();
    }
    Path::new(origin)
        .parent()
        .unwrap_or(Path::new(""))
        .join(path)
}

/// The scene `name` names in the file `origin`: a built-in scene, or a model file (its path
/// relative to `origin`'s directory).
///
/// # Errors
/// [`SceneError::UnknownScene`] for an unknown built-in name; [`SceneError::ModelRefused`]
/// carrying the model file's error (its place and what is wrong).
pub fn find_scene(name: &str, origin: &str) -> Result<&'static dyn Scene, SceneError> {
    if !names_a_file(name) {
        return scenes::find(name);
    }
    let path = relative_to(name, origin);
    tumble_model::load(&path)
        .map(|scene| scene as &'static dyn Scene)
        .map_err(|e| SceneError::ModelRefused {
            model: path.display().to_string(),
            message: e.to_string(),
        })
}
