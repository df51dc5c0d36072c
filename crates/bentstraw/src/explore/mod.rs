//! `bentstraw explore`: a live explorer in the browser, served by bentstraw itself on this
//! machine ([`bentstraw_server`]): the flags turned into the page's first view, the address
//! bound, the browser opened.

use bentstraw_optics::view::{CLASSIC_OBSERVER, CLASSIC_STRAW, CLASSIC_WATER_HEIGHT};
use std::io::Write;

use bentstraw_optics::scene::WATER_INDEX;
use bentstraw_optics::scene_file::SceneDescription;

use bentstraw_explore as api;

use crate::cli::ExploreArgs;
use crate::error::{fail, CliResult};
use bentstraw_io::gallery::GALLERY;

/// Runs `explore`.
pub fn run(args: &ExploreArgs) -> CliResult {
    let initial = initial_query(args)?;
    // The starting view obeys the same rules as the page's: refuse it before listening.
    let q = api::parse_query(&initial).map_err(crate::error::CliError)?;
    api::View::from_query(&q).map_err(crate::error::CliError)?;
    // `[::1]` as a URL writes it, or `::1`.
    let host = args
        .host
        .strip_prefix('[')
        .and_then(|h| h.strip_suffix(']'))
        .unwrap_or(&args.host);
    let listener = match std::net::TcpListener::bind((host, args.port)) {
        Ok(l) => l,
        Err(e) if e.kind() == std::io::ErrorKind::AddrInUse => {
            return fail(format!(
                "port {} on {} is busy (another program listens there): choose another with --port, or --port 0 for any free port",
                args.port, args.host
            ))
        }
        Err(e) => return fail(format!("cannot listen on {}:{}: {e}", args.host, args.port)),
    };
    let cannot =
        |e: std::io::Error| crate::error::CliError(format!("cannot listen on {}: {e}", args.host));
    let bound = listener.local_addr().map_err(cannot)?;
    if !bound.ip().is_loopback() {
        crate::progress::tell(&format!(
            "warning: listening on {}: anyone who can reach this machine over the network can use the explorer and make it compute (--host 127.0.0.1 keeps it to this machine)\n",
            bentstraw_server::url_host(bound)
        ));
    }
    // Every address includes this machine's own: the browser here opens that one.
    let shown = if bound.ip().is_unspecified() {
        let loopback: std::net::IpAddr = match bound {
            std::net::SocketAddr::V4(_) => std::net::Ipv4Addr::LOCALHOST.into(),
            std::net::SocketAddr::V6(_) => std::net::Ipv6Addr::LOCALHOST.into(),
        };
        std::net::SocketAddr::new(loopback, bound.port())
    } else {
        bound
    };
    let url = format!(
        "http://{}:{}/",
        bentstraw_server::url_host(shown),
        shown.port()
    );
    println!("bentstraw explore: open {url}  (Ctrl-C stops the server)");
    let _ = std::io::stdout().flush();
    if !args.no_open {
        open_browser(&url);
    }
    bentstraw_server::serve(listener, &initial).map_err(cannot)
}

/// The query of the view given on the command line (flags as the page's parameters): a scene file
/// and the flags that override it, or the flags, or by default the broken straw seen from the side
/// (as the page starts).
/// The assignment's values the page starts with.
struct Values {
    observer: [f64; 3],
    straw: [f64; 2],
    water_height: f64,
    n_water: f64,
    max_events: u32,
}

fn initial_query(a: &ExploreArgs) -> CliResult<String> {
    let v = &a.view;
    let mode = match a.mode {
        crate::cli::ModeArg::Course => "course",
        crate::cli::ModeArg::Fresnel => "fresnel",
    };
    let values = if let Some(path) = &v.scene {
        let loaded = crate::cli::load_scene(&v.source())?;
        match loaded.assignment_numbers().copied() {
            Some(scene) => Values {
                observer: loaded.observer.to_array(),
                straw: [scene.straw_x(), scene.straw_y()],
                water_height: scene.water_height(),
                n_water: scene.n_water(),
                max_events: scene.max_events(),
            },
            // A scene of the built-in gallery starts the page on it; another is refused, saying
            // what the page offers.
            None => {
                let f = loaded;
                let o = f.observer;
                let query = |stem: &str| {
                    format!(
                        "scene={stem}&observer={},{},{}&max-events={}&points={}&mode={mode}",
                        o.x, o.y, o.z, v.max_events, a.points
                    )
                };
                // A scene of the built-in gallery starts the page on it by name.
                if let Some((stem, _)) = GALLERY.iter().find(|(_, text)| {
                    SceneDescription::from_toml(text).is_ok_and(|d| d == f.description)
                }) {
                    return Ok(query(stem));
                }
                if v.straw.is_some() || v.water_height.is_some() || v.n_water.is_some() {
                    return fail(format!(
                        "explore shows {} as the file has it: --straw, --water-height and --n-water \
                         change only the assignment's kind of scene here (edit the file instead)",
                        f.name()
                    ));
                }
                // Any other file travels with the view, as the page's own scene file.
                let text = bentstraw_io::scene_input::read_scene_text(path)?;
                return Ok(format!(
                    "scene-file={}&observer={},{},{}&max-events={}&points={}&mode={mode}",
                    api::query_value(&text),
                    o.x,
                    o.y,
                    o.z,
                    v.max_events,
                    a.points
                ));
            }
        }
    } else {
        let o = v.observer.unwrap_or(CLASSIC_OBSERVER);
        let [x, y] = v.straw.unwrap_or(CLASSIC_STRAW);
        // Checked by the caller, with the page's own rules and messages.
        Values {
            observer: o,
            straw: [x, y],
            water_height: v.water_height.unwrap_or(CLASSIC_WATER_HEIGHT),
            n_water: v.n_water.unwrap_or(WATER_INDEX),
            max_events: v.max_events,
        }
    };
    Ok(format!(
        "observer={},{},{}&straw={},{}&water-height={}&n-water={}&max-events={}&points={}&mode={mode}",
        values.observer[0],
        values.observer[1],
        values.observer[2],
        values.straw[0],
        values.straw[1],
        values.water_height,
        values.n_water,
        values.max_events,
        a.points,
    ))
}

/// Opens `url` in the default browser if one can be found; says nothing if none.
fn open_browser(url: &str) {
    let candidates: &[(&str, &[&str])] = if cfg!(target_os = "macos") {
        &[("open", &[])]
    } else if cfg!(windows) {
        &[("cmd", &["/C", "start", ""])]
    } else {
        &[("xdg-open", &[]), ("sensible-browser", &[])]
    };
    for (program, before) in candidates {
        let child = std::process::Command::new(program)
            .args(*before)
            .arg(url)
            .stdin(std::process::Stdio::null())
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn();
        if let Ok(mut child) = child {
            // Reap it when it ends, so no zombie stays behind.
            std::thread::spawn(move || child.wait());
            return;
        }
    }
}
