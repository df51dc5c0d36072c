//! The explorer's page: one page for both engines. `bentstraw explore` serves it with the
//! native engine behind `/api/…`; the static site (`cargo xtask site`) ships it with the engine
//! compiled to WebAssembly, run by Web Workers. The page sends the same requests to either.

use bentstraw_io::escape::escape_html;

/// Which engine answers the page's requests.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Engine {
    /// `bentstraw explore`, over HTTP (`/api/…`).
    Server,
    /// The engine in WebAssembly, in the page's Web Workers (the static site).
    Wasm,
}

/// A file of the page: its name (a path relative to the page), its `Content-Type`, its text.
#[derive(Clone, Copy, Debug)]
pub struct PageFile {
    /// Name, relative to the page.
    pub name: &'static str,
    /// `Content-Type`.
    pub content_type: &'static str,
    /// The text.
    pub text: &'static str,
}

/// The page's HTML with its placeholders (the starting view, the engine).
const INDEX: &str = include_str!("../page/index.html");

/// The `Content-Type` of the page's scripts: module scripts must be served as JavaScript.
const JS: &str = "text/javascript; charset=utf-8";

/// The page's scripts that are workers, each started by a script (not modules of the page).
const WORKER_SCRIPTS: [&str; 2] = ["worker.js", "sw.js"];

/// The page's files other than its HTML ([`index_html`]).
pub const PAGE_FILES: [PageFile; 27] = [
    // The page's entry module (index.html loads it; it imports the others, each one concept).
    PageFile {
        name: "main.js",
        content_type: JS,
        text: include_str!("../page/main.js"),
    },
    // The page's texts in English and in French.
    PageFile {
        name: "i18n.js",
        content_type: JS,
        text: include_str!("../page/i18n.js"),
    },
    PageFile {
        name: "state.js",
        content_type: JS,
        text: include_str!("../page/state.js"),
    },
    PageFile {
        name: "geometry.js",
        content_type: JS,
        text: include_str!("../page/geometry.js"),
    },
    PageFile {
        name: "dom.js",
        content_type: JS,
        text: include_str!("../page/dom.js"),
    },
    PageFile {
        name: "engine.js",
        content_type: JS,
        text: include_str!("../page/engine.js"),
    },
    PageFile {
        name: "errors.js",
        content_type: JS,
        text: include_str!("../page/errors.js"),
    },
    PageFile {
        name: "quickscale.js",
        content_type: JS,
        text: include_str!("../page/quickscale.js"),
    },
    PageFile {
        name: "frames.js",
        content_type: JS,
        text: include_str!("../page/frames.js"),
    },
    PageFile {
        name: "draw.js",
        content_type: JS,
        text: include_str!("../page/draw.js"),
    },
    PageFile {
        name: "pointer.js",
        content_type: JS,
        text: include_str!("../page/pointer.js"),
    },
    PageFile {
        name: "sketch.js",
        content_type: JS,
        text: include_str!("../page/sketch.js"),
    },
    PageFile {
        name: "picture.js",
        content_type: JS,
        text: include_str!("../page/picture.js"),
    },
    PageFile {
        name: "lightpath.js",
        content_type: JS,
        text: include_str!("../page/lightpath.js"),
    },
    PageFile {
        name: "lesson.js",
        content_type: JS,
        text: include_str!("../page/lesson.js"),
    },
    PageFile {
        name: "outline.js",
        content_type: JS,
        text: include_str!("../page/outline.js"),
    },
    PageFile {
        name: "cloud.js",
        content_type: JS,
        text: include_str!("../page/cloud.js"),
    },
    PageFile {
        name: "maps.js",
        content_type: JS,
        text: include_str!("../page/maps.js"),
    },
    PageFile {
        name: "readout.js",
        content_type: JS,
        text: include_str!("../page/readout.js"),
    },
    PageFile {
        name: "controls.js",
        content_type: JS,
        text: include_str!("../page/controls.js"),
    },
    PageFile {
        name: "scenetext.js",
        content_type: JS,
        text: include_str!("../page/scenetext.js"),
    },
    PageFile {
        name: "editor.js",
        content_type: JS,
        text: include_str!("../page/editor.js"),
    },
    PageFile {
        name: "predict.js",
        content_type: JS,
        text: include_str!("../page/predict.js"),
    },
    PageFile {
        name: "sweep.js",
        content_type: JS,
        text: include_str!("../page/sweep.js"),
    },
    PageFile {
        name: "explorer.css",
        content_type: "text/css; charset=utf-8",
        text: include_str!("../page/explorer.css"),
    },
    PageFile {
        name: "worker.js",
        content_type: JS,
        text: include_str!("../page/worker.js"),
    },
    // The static site's copy of itself for opening without a network (the server's page does
    // not register it: it needs the server anyway).
    PageFile {
        name: "sw.js",
        content_type: JS,
        text: include_str!("../page/sw.js"),
    },
];

/// The page's HTML starting on the view of the query `initial` (empty: the address's, else the
/// default), its requests answered by `engine`, the engine's defaults in it.
pub fn index_html(initial: &str, engine: Engine) -> String {
    let engine = match engine {
        Engine::Server => "server",
        Engine::Wasm => "wasm",
    };
    // The view's defaults as the engine holds them: the page states none of its own. In a
    // <script> element only "</" could end it early; JSON allows "<" as \u003c.
    let defaults = String::from_utf8(crate::defaults_reply().body)
        .expect("JSON is UTF-8")
        .replace('<', "\\u003c");
    // Every module of the page fetched at once, not one level of imports after another.
    let modules: String = PAGE_FILES
        .iter()
        .filter(|f| f.content_type == JS && !WORKER_SCRIPTS.contains(&f.name))
        .map(|f| format!("<link rel=\"modulepreload\" href=\"{}\">\n", f.name))
        .collect();
    INDEX
        .replace("__MODULES__", &modules)
        .replace("__INITIAL_VIEW__", &escape_html(initial))
        .replace("__ENGINE__", engine)
        .replace("__DEFAULTS__", &defaults)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_page_names_its_engine_and_its_start_and_escapes_it() {
        let html = index_html("observer=1,0,0&x=\"<b>\"", Engine::Wasm);
        assert!(html.contains("data-engine=\"wasm\""), "{html}");
        assert!(html.contains("data-initial=\"observer=1,0,0&amp;x=&quot;&lt;b&gt;&quot;\""));
        assert!(!html.contains("__"));
        // The engine's defaults, readable by the page's script.
        let start = html
            .find("id=\"bentstraw-defaults\" type=\"application/json\">")
            .unwrap();
        let json = &html[html[start..].find('>').unwrap() + start + 1..];
        let json = &json[..json.find("</script>").unwrap()];
        let defaults: serde_json::Value = serde_json::from_str(json).unwrap();
        assert_eq!(defaults["points"], bentstraw_optics::view::DEFAULT_POINTS);
        // Every file is used: named by the page (its fetches aside) or imported by a module.
        let named: String = html
            .lines()
            .filter(|l| !l.contains("modulepreload"))
            .collect();
        for f in PAGE_FILES {
            let loaded_by_script = WORKER_SCRIPTS.contains(&f.name);
            let imported = PAGE_FILES
                .iter()
                .any(|g| g.text.contains(&format!("from \"./{}\"", f.name)));
            assert!(
                named.contains(f.name) || loaded_by_script || imported,
                "{}",
                f.name
            );
            // And each module is fetched at once.
            let preload = format!("<link rel=\"modulepreload\" href=\"{}\">", f.name);
            assert_eq!(
                html.contains(&preload),
                f.content_type == JS && !loaded_by_script,
                "{}",
                f.name
            );
        }
    }

    /// Every module the page imports is one of its files (the site's service worker keeps a copy
    /// of every file the site's build writes).
    #[test]
    fn every_module_imported_is_served() {
        let sw = PAGE_FILES.iter().find(|f| f.name == "sw.js").unwrap().text;
        assert!(sw.lines().any(|l| l.starts_with("const MANIFEST = null;")));
        for f in PAGE_FILES.iter().filter(|f| f.name.ends_with(".js")) {
            for line in f.text.lines().filter(|l| l.starts_with("import ")) {
                let name = line
                    .rsplit_once("from \"./")
                    .and_then(|(_, n)| n.strip_suffix("\";"))
                    .unwrap_or_else(|| panic!("{}: {line}", f.name));
                let served = PAGE_FILES.iter().find(|g| g.name == name);
                assert!(served.is_some(), "{} imports {name}", f.name);
                assert_eq!(served.unwrap().content_type, JS, "{name}");
            }
        }
    }
}
