//! The live view in the book: the page `scripts/web.sh` builds (plait's
//! engine on WebGPU, `crates/plait-web`) copied under `live/`, and on every
//! technique and gallery page a link that opens it with that page's pipeline
//! and choices (`live/index.html?pipeline=…&set=…`). A reader whose browser
//! has no WebGPU is told so on the page, beside its static pictures.

use std::path::Path;

use crate::error::BookError;
use crate::plait_cmd::Figure;

/// Where the site goes in the built book.
pub const DIR: &str = "live";

/// The live view's URL for `figure`, relative to the page at `page` (its
/// path under `src/`).
pub fn url(page: &str, figure: &Figure) -> String {
    let up = "../".repeat(page.matches('/').count());
    let mut url = format!("{up}{DIR}/index.html?pipeline={}", encode(&figure.pipeline));
    for set in &figure.sets {
        url.push_str(&format!("&set={}", encode(set)));
    }
    url
}

/// Percent-encodes what a query value cannot hold as is.
fn encode(value: &str) -> String {
    value
        .chars()
        .map(|c| match c {
            'A'..='Z' | 'a'..='z' | '0'..='9' | '.' | '_' | '-' => c.to_string(),
            c => c.to_string().bytes().map(|b| format!("%{b:02X}")).collect(),
        })
        .collect()
}

/// The page's "Live" section: the link, and a note that shows only where
/// the browser offers no WebGPU adapter (no `navigator.gpu`, or no adapter
/// from it: headless Chromium without a GPU has the one and not the other),
/// saying why the pictures above are all there is.
pub fn section(page: &str, figure: &Figure) -> String {
    let sets = if figure.sets.is_empty() {
        String::new()
    } else {
        format!(" with `{}`", figure.sets.join(" "))
    };
    format!(
        "\n## Live\n\n[Open `{}`{sets} in the live view]({}): plait's engine compiled to \
         WebAssembly renders it on the small built-in scene in your browser with WebGPU; choose \
         other techniques and params there, drag the picture to orbit the camera.\n\n\
         <p class=\"plait-no-webgpu\" hidden><strong>This browser offers no WebGPU \
         adapter</strong> (<code>navigator.gpu</code> is missing, or its \
         <code>requestAdapter()</code> gives none), so the live view cannot run here: the \
         pictures on this page are static renders made with <code>plait render</code>.</p>\n\
         <script>(async () => {{ const gpu = navigator.gpu; \
         if (!(gpu && await gpu.requestAdapter().catch(() => null))) \
         document.querySelectorAll('.plait-no-webgpu').forEach((p) => {{ p.hidden = false; }}); \
         }})();</script>\n",
        figure.pipeline,
        url(page, figure)
    )
}

/// Copies the site (`scripts/web.sh`'s output) into the built book.
pub fn copy_site(site: &Path, out: &Path) -> Result<(), BookError> {
    let dest = out.join(DIR);
    std::fs::create_dir_all(&dest).map_err(BookError::io(&dest))?;
    let entries = std::fs::read_dir(site).map_err(BookError::io(site))?;
    for entry in entries {
        let from = entry.map_err(BookError::io(site))?.path();
        if from.is_file() {
            let to = dest.join(from.file_name().unwrap_or_default());
            std::fs::copy(&from, &to).map_err(BookError::io(&from))?;
        }
    }
    if !dest.join("index.html").is_file() {
        return Err(BookError::content(
            site,
            "no index.html: not the live view's site (bash scripts/web.sh builds it)".to_owned(),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_link_chooses_the_pages_pipeline_and_techniques() {
        let figure = Figure {
            pipeline: "occupancy.toml".into(),
            sets: vec!["techniques.shading=marschner".into()],
        };
        assert_eq!(
            url("techniques/shading/marschner.md", &figure),
            "../../live/index.html?pipeline=occupancy.toml&set=techniques.shading%3Dmarschner"
        );
        let plain = Figure {
            pipeline: "forward.toml".into(),
            sets: Vec::new(),
        };
        assert_eq!(
            url("pipelines/forward.md", &plain),
            "../live/index.html?pipeline=forward.toml"
        );
    }
}
