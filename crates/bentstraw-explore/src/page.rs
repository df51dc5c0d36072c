//! The explorer's page: one page for both engines. `bentstraw explore` serves it with the
//! native engine behind `/api/…`; the static site (`cargo xtask site`) ships it with the engine
//! compiled to WebAssembly, run by Web Workers. The page sends the same requests to either.

use bentstraw_outputs::escape::escape_html;

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

/// The page's files other than its HTML ([`index_html`]).
pub const PAGE_FILES: [PageFile; 5] = [
    // The page's texts in English and in French (loaded before explorer.js).
    PageFile {
        name: "i18n.js",
        content_type: "text/javascript; charset=utf-8",
        text: include_str!("../page/i18n.js"),
    },
    PageFile {
        name: "explorer.js",
        content_type: "text/javascript; charset=utf-8",
        text: include_str!("../page/explorer.js"),
    },
    PageFile {
        name: "explorer.css",
        content_type: "text/css; charset=utf-8",
        text: include_str!("../page/explorer.css"),
    },
    PageFile {
        name: "worker.js",
        content_type: "text/javascript; charset=utf-8",
        text: include_str!("../page/worker.js"),
    },
    // The static site's copy of itself for opening without a network (the server's page does
    // not register it: it needs the server anyway).
    PageFile {
        name: "sw.js",
        content_type: "text/javascript; charset=utf-8",
        text: include_str!("../page/sw.js"),
    },
];

/// The page's HTML starting on the view of the query `initial` (empty: the address's, else the
/// default), its requests answered by `engine`.
pub fn index_html(initial: &str, engine: Engine) -> String {
    let engine = match engine {
        Engine::Server => "server",
        Engine::Wasm => "wasm",
    };
    INDEX
        .replace("__INITIAL_VIEW__", &escape_html(initial))
        .replace("__ENGINE__", engine)
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
        for f in PAGE_FILES {
            let loaded_by_script = ["worker.js", "sw.js"].contains(&f.name);
            assert!(html.contains(f.name) || loaded_by_script, "{}", f.name);
        }
    }
}
