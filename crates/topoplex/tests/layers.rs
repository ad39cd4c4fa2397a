//! The floors of the core library (ARCHITECTURE.md): every module of `src/` imports only from the
//! modules below it. Reads each file's `crate::` paths (in `use` lines, groups included, and in
//! code) outside comments and outside the unit tests at the end of a file, and fails naming the
//! file, the line and the climb. A new top-level module must be given its floor here.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The floors from the ground up; within a floor, the order in which its rooms may import each
/// other (a room imports only rooms listed before it).
const FLOORS: &[(&str, &[&str])] = &[
    (
        "tools",
        &[
            "error",
            "alloc",
            "sys",
            "parallel",
            "scratch",
            "union_find",
            "mapped",
        ],
    ),
    ("model", &["complex"]),
    ("io", &["io"]),
    ("relation API", &["relation"]),
    ("test support", &["oracle", "fixtures", "testing"]),
    ("section codec", &["codec"]),
    ("structures", &["structures"]),
    ("live mesh", &["live"]),
    ("kind registry", &["family"]),
    ("saved file", &["store"]),
    ("algorithms", &["decompose", "simplify"]),
];
// Above the core crate: the C ABI (crates/topoplex-ffi) and the CLI with `report` (the root
// package), which import the core only through its public API.

/// Macros exported at the crate root (`crate::name!`), by the room that defines them.
const MACROS: &[(&str, &str)] = &[("persist_fields", "codec")];

fn rank() -> BTreeMap<&'static str, (usize, &'static str)> {
    let mut r = BTreeMap::new();
    for (floor, rooms) in FLOORS {
        for room in rooms.iter() {
            r.insert(*room, (r.len(), *floor));
        }
    }
    r
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The top-level module a file belongs to (`None` for the crate root and binaries).
fn room_of(src: &Path, file: &Path) -> Option<String> {
    let rel = file.strip_prefix(src).unwrap();
    let first = rel.components().next()?.as_os_str().to_str()?.to_string();
    let room = first.strip_suffix(".rs").unwrap_or(&first).to_string();
    (room != "lib" && room != "main" && room != "bin").then_some(room)
}

/// The code of a file without comments and without the trailing `#[cfg(test)]` module.
fn code_lines(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.starts_with("#[cfg(test)]") {
            break;
        }
        let code = match line.find("//") {
            Some(at) => &line[..at],
            None => line,
        };
        out.push((i + 1, code.to_string()));
    }
    out
}

/// The rooms a statement names after `crate::`: the first segment, or every first segment of a
/// `crate::{a::…, b}` group.
fn named_rooms(code: &str) -> Vec<String> {
    let mut rooms = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find("crate::") {
        let before = &rest[..at];
        let after = &rest[at + "crate::".len()..];
        rest = after;
        // `$crate::` in macros counts too; an identifier ending in `crate` (e.g. `my_crate::`)
        // does not.
        if before.ends_with(|c: char| c.is_alphanumeric() || c == '_') {
            continue;
        }
        if let Some(group) = after.strip_prefix('{') {
            let mut depth = 1;
            let mut item = String::new();
            for c in group.chars() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 1 => {
                        rooms.push(first_ident(&item));
                        item.clear();
                        continue;
                    }
                    _ => {}
                }
                if depth == 0 {
                    break;
                }
                if depth == 1 {
                    item.push(c);
                } else if item.is_empty() {
                    item.push(' ');
                }
            }
            rooms.push(first_ident(&item));
        } else {
            rooms.push(first_ident(after));
        }
    }
    rooms.retain(|r| !r.is_empty() && r.chars().next().unwrap().is_lowercase());
    rooms
}

fn first_ident(s: &str) -> String {
    s.trim()
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect()
}

/// Joins each `use crate::{…};` spread over several lines into its first line.
fn statements(lines: &[(usize, String)]) -> Vec<(usize, String)> {
    let mut out: Vec<(usize, String)> = Vec::new();
    let mut open: Option<(usize, String)> = None;
    for (n, l) in lines {
        if let Some((at, mut s)) = open.take() {
            s.push_str(l);
            if l.contains(';') {
                out.push((at, s));
            } else {
                open = Some((at, s));
            }
            continue;
        }
        if l.trim_start().starts_with("use ")
            || l.trim_start().starts_with("pub use ")
            || l.trim_start().starts_with("pub(crate) use ")
        {
            if l.contains(';') {
                out.push((*n, l.clone()));
            } else {
                open = Some((*n, l.clone()));
            }
        } else {
            out.push((*n, l.clone()));
        }
    }
    out
}

fn climbs() -> Vec<String> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let rank = rank();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    files.sort();
    let mut found = Vec::new();
    for file in &files {
        let Some(room) = room_of(&src, file) else {
            continue;
        };
        let Some(&(mine, my_floor)) = rank.get(room.as_str()) else {
            found.push(format!(
                "{}: module `{room}` has no floor in tests/layers.rs (FLOORS)",
                file.display()
            ));
            continue;
        };
        let text = std::fs::read_to_string(file).unwrap();
        for (line, stmt) in statements(&code_lines(&text)) {
            for mut target in named_rooms(&stmt) {
                if let Some((_, home)) = MACROS.iter().find(|(m, _)| *m == target) {
                    target = home.to_string();
                }
                if target == room {
                    continue;
                }
                match rank.get(target.as_str()) {
                    Some(&(theirs, their_floor)) if theirs > mine => found.push(format!(
                        "{}:{line}: `{room}` ({my_floor}) imports `{target}` ({their_floor}), \
                         which stands above it",
                        file.display()
                    )),
                    Some(_) => {}
                    None => found.push(format!(
                        "{}:{line}: `crate::{target}` is not a module with a floor",
                        file.display()
                    )),
                }
            }
        }
    }
    found
}

#[test]
fn every_import_goes_down_a_floor() {
    let found = climbs();
    assert!(
        found.is_empty(),
        "{} import(s) climb:\n{}",
        found.len(),
        found.join("\n")
    );
}

#[test]
fn the_reader_sees_groups_macros_and_not_comments() {
    assert_eq!(
        named_rooms("use crate::{complex::{A, B}, io::C, parallel};"),
        ["complex", "io", "parallel"]
    );
    assert_eq!(named_rooms("impl $crate::codec::Field for T"), ["codec"]);
    assert!(named_rooms("use my_crate::x;").is_empty());
    let lines = code_lines("use crate::a; // crate::b\n#[cfg(test)]\nuse crate::c;");
    assert_eq!(lines.len(), 1);
    assert_eq!(named_rooms(&lines[0].1), ["a"]);
    let joined = statements(&[
        (1, "use crate::{".into()),
        (2, "    io::X,".into()),
        (3, "};".into()),
    ]);
    assert_eq!(named_rooms(&joined[0].1), ["io"]);
}
