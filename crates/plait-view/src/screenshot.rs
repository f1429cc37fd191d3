//! Writing the viewer's `--screenshot` (and any PNG it writes) whole or not
//! at all.

use std::path::{Path, PathBuf};

/// Write a PNG whole or not at all (a temporary file renamed into place).
pub fn write_png(path: &Path, image: &image::RgbaImage) -> Result<(), String> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| e.to_string())?;
    let mut builder = tempfile::Builder::new();
    builder.prefix(".plait-");
    // An ordinary file's permissions (0666 less the umask, as `plait render`
    // writes): tempfile's default, 0600, would stay on the renamed screenshot.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut tmp = builder
        .tempfile_in(&dir)
        .map_err(|e| format!("cannot write in {}: {e}", dir.display()))?;
    std::io::Write::write_all(&mut tmp, &png).map_err(|e| e.to_string())?;
    tmp.persist(path).map_err(|e| e.error.to_string())?;
    Ok(())
}
