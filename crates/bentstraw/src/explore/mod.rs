//! `bentstraw explore`: a live explorer in the browser, served by bentstraw itself on this
//! machine ([`bentstraw_server`]): the flags turned into the page's first view, the address
//! bound, the browser opened.

use std::io::Write;

use bentstraw_optics::scene_file::SceneDescription;
use bentstraw_optics::setup::SceneValues;
use bentstraw_optics::view::PictureSpec;

use bentstraw_explore as api;

use crate::cli::{ExploreArgs, ModeArg};
use crate::error::{fail, CliResult};
use bentstraw_io::gallery::GALLERY;
use bentstraw_io::view_spec::{SceneFile, ViewSpec, PAGE_SCENE_FILE};

/// Runs `explore`.
pub fn run(args: &ExploreArgs) -> CliResult {
    let initial = initial_query(args)?;
    let bad: Vec<String> = args
        .allow_host
        .iter()
        .filter(|name| !is_host_name(name))
        .map(|name| format!("--allow-host {name:?} is not a machine's name: letters, digits, '-' and '.', at most 253 characters"))
        .collect();
    if !bad.is_empty() {
        return fail(bad.join("\n"));
    }
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
    // Reachable from other machines: only with the token printed in the address.
    let token = (!bound.ip().is_loopback()).then(bentstraw_server::new_token);
    if !bound.ip().is_loopback() {
        crate::progress::tell(&format!(
            "warning: listening on {}: whoever has the address below (with its token) can use the explorer from the network and make it compute (--host 127.0.0.1 keeps it to this machine)\n",
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
        "http://{}:{}/{}",
        bentstraw_server::url_host(shown),
        shown.port(),
        token
            .as_ref()
            .map_or(String::new(), |t| format!("?token={t}"))
    );
    println!("bentstraw explore: open {url}  (Ctrl-C stops the server)");
    let _ = std::io::stdout().flush();
    if !args.no_open {
        open_browser(&url);
    }
    let access = bentstraw_server::Access {
        allow_hosts: args.allow_host.clone(),
        token,
    };
    bentstraw_server::serve(listener, &initial, access).map_err(cannot)
}

/// The query of the view given on the command line (flags as the page's parameters): a scene file
/// and the flags that override it, or the flags, or by default the classic first view (as the
/// page starts).
fn initial_query(a: &ExploreArgs) -> CliResult<String> {
    let v = &a.view;
    let mut view = ViewSpec {
        picture: PictureSpec {
            fresnel: a.mode == ModeArg::Fresnel,
            ..PictureSpec::default()
        },
        points: a.points,
        ..ViewSpec::default()
    };
    let asked = v.view()?;
    let Some(file) = &asked.scene else {
        // The flags, else the classic view's; checked by the caller, with the page's own rules
        // and messages.
        let classic = view.values;
        view.values = SceneValues {
            observer: v.observer.or(classic.observer),
            straw: v.straw.or(classic.straw),
            water_height: v.water_height.or(classic.water_height),
            n_water: v.n_water,
            max_events: v.max_events,
            wavelength: v.wavelength,
        };
        return Ok(view.to_query());
    };
    let loaded = crate::cli::load_scene(&asked)?;
    let observer = Some(loaded.observer.to_array());
    // A file of the assignment's kind (named by its values, not by the file) starts the page on
    // its glass: the flags' values, else the file's.
    if let (None, Some(glass)) = (&loaded.name, loaded.description.spec_scene()) {
        view.values = SceneValues {
            observer,
            straw: Some(v.straw.unwrap_or([glass.straw_x(), glass.straw_y()])),
            water_height: Some(v.water_height.unwrap_or(glass.water_height())),
            n_water: Some(v.n_water.unwrap_or(glass.n_water())),
            max_events: v.max_events,
            wavelength: v.wavelength,
        };
        return Ok(view.to_query());
    }
    // Any other scene is seen as the file has it, from the file's observer or the flag's.
    view.values = SceneValues {
        observer,
        max_events: v.max_events,
        wavelength: v.wavelength,
        ..SceneValues::default()
    };
    // A scene of the built-in gallery starts the page on it by name.
    if let Some((stem, _)) = GALLERY
        .iter()
        .find(|(_, text)| SceneDescription::from_toml(text).is_ok_and(|d| d == loaded.description))
    {
        view.scene = SceneFile::gallery(stem);
        return Ok(view.to_query());
    }
    // Another is refused with those flags, saying what the page offers.
    if v.straw.is_some() || v.water_height.is_some() || v.n_water.is_some() {
        return fail(format!(
            "explore shows {} as the file has it: --straw, --water-height and --n-water \
             change only the assignment's kind of scene here (edit the file instead)",
            loaded.name()
        ));
    }
    // Any other file travels with the view, as the page's own scene file.
    view.scene = Some(SceneFile {
        name: PAGE_SCENE_FILE.to_string(),
        text: file.text.clone(),
    });
    Ok(view.to_query())
}

/// Whether `name` can be a machine's name in an address: letters, digits, '-' and '.'.
fn is_host_name(name: &str) -> bool {
    !name.is_empty()
        && name.len() <= 253
        && name
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'.')
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
