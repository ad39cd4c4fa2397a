//! `topoplex`: report on a complex and dump its relations through any structure.
//!
//! Error contract: every failure — a usage error, an unreadable input, an output that cannot be
//! written (full disk) — exits 1 with one bounded, escaped line on stderr (`topoplex: ...`);
//! nothing panics on I/O; a closed pipe on stdout (`... | head -1`) ends the run quietly with
//! exit 0 ([`BROKEN_PIPE`]). A subcommand is a function returning `Result<(), String>` called
//! from [`run`]; it reads inputs with [`load`] (which applies `--max-simplices` and `--verify`)
//! and writes stdout with [`print`] or through [`output_error`].

use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::{Mutex, mpsc};
use std::time::Duration;

use clap::{CommandFactory, Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use topoplex::error::{echo, echo_path, one_line};
use topoplex::io::write::Format;
use topoplex::relation::sort_rows;
use topoplex::store::Saved;
use topoplex::{Budget, Complex, StructureKind, Topology, fixtures};

#[derive(Parser)]
#[command(
    name = "topoplex",
    version,
    about = "Topological data structures for arbitrary simplicial complexes"
)]
struct Cli {
    /// Most simplices an input's closure may have (by an upper bound, or an exact count when
    /// the bound is within 16 times the limit), or `unlimited`. Default: max(2^20, 64 × the input's vertex ids and declared
    /// vertices), so a few bytes of high-dimensional simplices cannot expand into gigabytes.
    #[arg(long, global = true, value_name = "N", value_parser = parse_max_simplices)]
    max_simplices: Option<u64>,
    /// Threads for building structures, 1 to 256 (default: TOPOPLEX_THREADS, else every core).
    #[arg(long, global = true, value_name = "N")]
    threads: Option<usize>,
    /// Check a saved (.tpx) input fully before using it, as `verify` does: every checksum, the
    /// complex, the structure's invariants and its agreement with the complex (reads the whole
    /// file). Mesh inputs are always checked fully by reading them.
    #[arg(long, global = true)]
    verify: bool,
    /// Fan every convex planar polygon of a mesh input into triangles from its first vertex
    /// (winding and the polygon's labels and fields kept on each triangle): faces of more than
    /// 3 vertices in OFF, OBJ and PLY, polygon and quad cells in legacy VTK, Gmsh quadrangles.
    /// A polygon that is not planar (beyond 1e-6 × its size), not convex, degenerate, repeats a
    /// vertex or has no coordinates is refused with the reason. Without it, polygons are
    /// refused.
    #[arg(long, global = true)]
    triangulate: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The survey's comparison tables for each file: census (wire edges, dangling faces, C_e,
    /// C_v − n_0, IQM components, non-manifold simplices), every structure's storage, build time
    /// and time per retrieved element for each relation family (sampled queries).
    Report {
        /// .off, .obj, .mesh, .simplices or .tpx files; without any, a built-in example complex with
        /// a wire edge, a dangling triangle, a tetrahedron and a non-manifold vertex and edge.
        files: Vec<PathBuf>,
        /// Print JSON (one object for one dataset, an array for several) instead of Markdown.
        #[arg(long, conflicts_with = "csv")]
        json: bool,
        /// Print CSV, one row per dataset and structure, instead of Markdown.
        #[arg(long)]
        csv: bool,
        /// Also write bar charts of storage and timings to this SVG file.
        #[arg(long, value_name = "FILE")]
        svg: Option<PathBuf>,
    },
    /// Print R_{P,Q}: one line per P-simplex, `σ;τ1;τ2...`, all in ascending lexicographic order.
    Relation {
        file: PathBuf,
        /// ig, sig, ia, iqm, nmia, ts, pe, le, de, or iastar (the live complex: top simplices and
        /// vertex stars, every other simplex generated on each query).
        #[arg(long)]
        structure: String,
        /// P,Q (for example 1,2: the triangles around each edge).
        #[arg(long, value_parser = parse_pq)]
        relation: (usize, usize),
        /// Only this P-simplex, given as vertex ids ("V0 V1 ...").
        #[arg(long)]
        simplex: Option<String>,
    },
    /// Build a structure and save it with its complex as a .tpx file, which every command takes
    /// as input and opens by memory mapping (no parsing, no build).
    Save {
        /// .off, .obj, .mesh, .simplices or .tpx input.
        file: PathBuf,
        /// ig, sig, ia, iqm, nmia, ts, pe, le, de, or iastar (the live complex, opened back
        /// editable); without it, only the complex is saved.
        #[arg(long)]
        structure: Option<String>,
        /// The .tpx file to write.
        #[arg(long)]
        out: PathBuf,
        #[command(flatten)]
        data: DropData,
    },
    /// Check a saved file fully: every section's checksum, the saved complex, the saved
    /// structure's invariants, and that the structure is the one its complex builds.
    Verify {
        /// The .tpx file.
        file: PathBuf,
    },
    /// Cut the complex into its IQM components (the standard decomposition into initial
    /// quasi-manifolds) and write each as its own file, plus gluing.json mapping every
    /// component's local vertex ids back to the original ids.
    Decompose {
        file: PathBuf,
        /// Output directory (created if missing). It must be empty, unless --force.
        #[arg(long)]
        out: PathBuf,
        /// Write into a non-empty --out directory, first deleting an earlier decomposition's
        /// files there (component_<i>.<ext> in any output format, gluing.json; other files are kept).
        /// The input is never overwritten or deleted.
        #[arg(long)]
        force: bool,
        /// Write every component in this format (any `convert --format` name) instead of by
        /// dimension; refused, writing nothing, if it cannot hold a component.
        #[arg(long)]
        format: Option<String>,
        #[command(flatten)]
        data: DropData,
    },
    /// Read INPUT and write it to OUTPUT (formats by extension): the top simplices in input
    /// order and winding, isolated vertices and wire edges kept, coordinates bit for bit, and
    /// every attribute (labels, fields; with listed-simplex data every listed simplex is
    /// written). A format that cannot hold the complex or an attribute is refused with the
    /// reason, writing nothing.
    Convert {
        input: PathBuf,
        output: PathBuf,
        /// Output format (see README: off, obj, mesh, simplices, ply, stl, vtk, vtu, msh, and
        /// -binary variants) instead of OUTPUT's extension.
        #[arg(long, conflicts_with = "census")]
        format: Option<String>,
        /// Write the non-manifold census instead (OUTPUT must end in .vtk): the top simplices
        /// plus one cell per non-manifold edge and triangle, with fields non_manifold_vertex,
        /// role and iqm_component for ParaView.
        #[arg(long)]
        census: bool,
        /// Round every coordinate to the nearest 32-bit float before writing (what STL
        /// stores: without it STL refuses coordinates that are not exactly such floats).
        /// Opt-in because it changes the numbers; a coordinate beyond the 32-bit range is
        /// refused, and vertices that then coincide are still refused by STL.
        #[arg(long, conflicts_with = "census")]
        round_f32: bool,
        #[command(flatten)]
        data: DropData,
    },
    /// Quadric-error edge-contraction simplification (Garland–Heckbert, any dimension) down to
    /// about RATIO × the input's top simplices; the output format follows its extension (any
    /// format `convert` writes).
    Simplify {
        input: PathBuf,
        /// Output file.
        #[arg(long)]
        out: PathBuf,
        /// Fraction of the top simplices to keep, in (0, 1].
        #[arg(long)]
        ratio: f64,
        /// Contract only edges satisfying the link condition: Betti numbers and manifoldness
        /// are kept.
        #[arg(long)]
        preserve_topology: bool,
        /// Keep the regions of this integer label (e.g. gmsh:physical, medit:ref) apart: no
        /// contraction merges two regions across their interface or erases one; interface
        /// vertices move only along their interface, corners where three or more meet stay.
        #[arg(long, value_name = "NAME")]
        keep_regions: Option<String>,
        #[command(flatten)]
        data: DropData,
    },
}

/// `--drop-data`, on every command that writes: attributes the output should not carry.
#[derive(clap::Args, Debug, Default)]
struct DropData {
    /// Drop the attribute NAME (labels or fields, e.g. medit:ref, gmsh:physical) before
    /// writing, every attribute with `all`, or only the names of labels (Gmsh's
    /// $PhysicalNames) with `label-names`; repeatable. Without it, data the output cannot hold
    /// is an error, never dropped silently.
    #[arg(long = "drop-data", value_name = "NAME|all")]
    names: Vec<String>,
}

impl DropData {
    /// Removes the named attributes from `complex`; naming one it does not have is an error
    /// listing those it has.
    fn apply(&self, complex: &mut Complex) -> Result<(), String> {
        if self.names.is_empty() {
            return Ok(());
        }
        let mut at = complex.take_attributes();
        for name in &self.names {
            if name == "all" {
                at.clear();
            } else if name == "label-names" && at.find(name).is_none() {
                if !at.remove_label_names() {
                    return Err("--drop-data label-names: the input names no labels".into());
                }
            } else if !at.remove(name) {
                let mut have: Vec<String> =
                    at.iter().map(|a| format!("'{}'", echo(&a.name))).collect();
                have.dedup();
                return Err(format!(
                    "--drop-data '{}': the input has no such attribute ({})",
                    echo(name),
                    if have.is_empty() {
                        "it has none".to_string()
                    } else {
                        format!("it has {}", have.join(", "))
                    }
                ));
            }
        }
        complex.set_attributes(at).map_err(|e| e.to_string())
    }
}

/// Refuses to go on when `complex` carries attributes that `what` does not carry yet: never
/// dropped silently.
fn refuse_data(complex: &Complex, what: &str) -> Result<(), String> {
    match complex.attributes().iter().next() {
        None => Ok(()),
        Some(a) => Err(format!(
            "{what} does not carry attributes yet, and the input has {}; drop them explicitly \
             with --drop-data '{}' (or all)",
            a.describe(),
            echo(&a.name)
        )),
    }
}

fn parse_max_simplices(s: &str) -> Result<u64, String> {
    if s == "unlimited" {
        return Ok(u64::MAX);
    }
    s.parse::<u64>()
        .map_err(|_| "expected a number of simplices or `unlimited`".to_string())
}

fn parse_pq(s: &str) -> Result<(usize, usize), String> {
    let (p, q) = s.split_once(',').ok_or("expected P,Q such as 1,2")?;
    let num = |t: &str| {
        t.trim()
            .parse::<usize>()
            .map_err(|_| format!("`{}` is not a dimension", echo(t)))
    };
    Ok((num(p)?, num(q)?))
}

/// The budget of every input (from `--max-simplices`; a mutex rather than a once-cell so the
/// CLI can be run several times in one process, as the CLI fuzz target does).
static BUDGET: Mutex<Option<u64>> = Mutex::new(None);

/// `--verify` (an atomic for the same reason as [`BUDGET`]).
static VERIFY: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// `--triangulate` (an atomic for the same reason as [`BUDGET`]).
static TRIANGULATE: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// The `Err` of a write to a closed pipe (`topoplex relation ... | head -1`): [`main`] exits
/// quietly with status 0, as ripgrep does (the reader wanted no more).
pub const BROKEN_PIPE: &str = "writing output: broken pipe";

fn main() -> ExitCode {
    // Keeps `simplify`'s peak RSS at its live heap: glibc's default dynamic mmap threshold left
    // ~40 MB of freed memory resident on a 1.2M-triangle mesh (docs/benchmarks.md).
    topoplex::sys::fix_malloc_thresholds_for_executable();
    match cli(std::env::args_os()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(msg) if msg == BROKEN_PIPE => ExitCode::SUCCESS,
        Err(msg) => fail(&msg),
    }
}

/// The whole CLI on an argument list (program name first): `Ok` is exit 0, `Err` the message
/// of exit 1, which [`main`] writes as one line. Also run in-process by the CLI fuzz target
/// (fuzz/fuzz_targets/cli_args.rs), which includes this file as a module.
pub fn cli(args: impl IntoIterator<Item = std::ffi::OsString>) -> Result<(), String> {
    use clap::FromArgMatches;
    let cli = command()
        .try_get_matches_from(args)
        .and_then(|m| Cli::from_arg_matches(&m))
        .map_err(|e| clap_outcome(&e));
    let cli = match cli {
        Ok(cli) => cli,
        Err(outcome) => return outcome,
    };
    *BUDGET.lock().unwrap_or_else(|e| e.into_inner()) = cli.max_simplices;
    VERIFY.store(cli.verify, std::sync::atomic::Ordering::Relaxed);
    TRIANGULATE.store(cli.triangulate, std::sync::atomic::Ordering::Relaxed);
    topoplex::parallel::threads_from_env()?;
    if let Some(n) = cli.threads {
        let n = topoplex::parallel::check_threads(n).map_err(|e| format!("--threads: {e}"))?;
        topoplex::parallel::set_threads(n);
    }
    run(cli.command)
}

/// The extensions read and written, from the one format table ([`Format::ALL`]): `.off, .obj,
/// ... or .msh`.
fn extensions() -> String {
    let mut exts: Vec<&str> = Vec::new();
    for f in Format::ALL {
        if !exts.contains(&f.extension()) {
            exts.push(f.extension());
        }
    }
    let dotted: Vec<String> = exts.iter().map(|e| format!(".{e}")).collect();
    match dotted.split_last() {
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// The CLI's clap command, its help texts on formats written from the format table, so that
/// they name every format the readers and writers know.
fn command() -> clap::Command {
    let input = format!(
        "Input: {} (by extension), or a saved file (known by its magic number, .tpx)",
        extensions()
    );
    let names: Vec<&str> = Format::ALL.iter().map(|f| f.name()).collect();
    let format = format!(
        "Output format, one of: {} (instead of OUTPUT's extension)",
        names.join(", ")
    );
    let output = format!("Output file: {} (format by extension)", extensions());
    let patch = |c: clap::Command| {
        match c.get_name() {
        "report" => c.mut_arg("files", |a| {
            a.help(format!(
                "{input}; without any, a built-in example complex with a wire edge, a dangling triangle, a tetrahedron and a non-manifold vertex and edge"
            ))
        }),
        "relation" | "save" | "decompose" => c.mut_arg("file", |a| a.help(&input)),
        "convert" => c
            .mut_arg("input", |a| a.help(&input))
            .mut_arg("output", |a| a.help(&output))
            .mut_arg("format", |a| a.help(&format)),
        "simplify" => c
            .mut_arg("input", |a| a.help(&input))
            .mut_arg("out", |a| a.help(&output)),
        _ => c,
    }
    };
    // Every subcommand in its order (mut_subcommand moves the one it changes to the end).
    let cli = Cli::command();
    let names: Vec<String> = cli
        .get_subcommands()
        .map(|c| c.get_name().to_string())
        .collect();
    names
        .iter()
        .fold(cli, |cli, name| cli.mut_subcommand(name, patch))
}

/// One arm per subcommand.
fn run(command: Command) -> Result<(), String> {
    match command {
        Command::Report {
            files,
            json,
            csv,
            svg,
        } => report(&files, json, csv, svg.as_deref()),
        Command::Relation {
            file,
            structure,
            relation,
            simplex,
        } => dump_relation(file, &structure, relation, simplex),
        Command::Decompose {
            file,
            out,
            force,
            format,
            data,
        } => decompose(&file, &out, force, format.as_deref(), &data),
        Command::Convert {
            input,
            output,
            format,
            census,
            round_f32,
            data,
        } => convert(&input, &output, format.as_deref(), census, round_f32, &data),
        Command::Save {
            file,
            structure,
            out,
            data,
        } => save(&file, structure.as_deref(), &out, &data),
        Command::Verify { file } => verify(&file),
        Command::Simplify {
            input,
            out,
            ratio,
            preserve_topology,
            keep_regions,
            data,
        } => simplify(
            &input,
            &out,
            (ratio, preserve_topology, keep_regions.as_deref()),
            &data,
        ),
    }
}

/// Writes `topoplex: <msg>` as one bounded, escaped line on stderr and returns exit status 1.
/// A stderr that cannot be written (closed, full) is ignored: the status still tells.
fn fail(msg: &str) -> ExitCode {
    let line = one_line(msg);
    let _ = writeln!(std::io::stderr().lock(), "topoplex: {line}");
    ExitCode::FAILURE
}

/// clap's outcome when parsing fails: `--help`/`--version` print to stdout (exit 0, or 1 when
/// stdout cannot take them); every usage error becomes one line and exit 1 (clap's own is
/// several lines and exit 2).
fn clap_outcome(e: &clap::Error) -> Result<(), String> {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => print(&e.render().to_string()),
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let names: Vec<String> = command()
                .get_subcommands()
                .map(|c| c.get_name().to_string())
                .filter(|n| n != "help")
                .collect();
            Err(format!(
                "no command given (one of: {}; see topoplex --help)",
                names.join(", ")
            ))
        }
        _ => Err(usage_line(&e.render().to_string())),
    }
}

/// clap's rendered error as one line: its first paragraph (the error and, for missing
/// arguments, their list) joined, without the usage block and tips that follow.
fn usage_line(rendered: &str) -> String {
    let first = rendered.trim_start().split("\n\n").next().unwrap_or("");
    let joined: Vec<&str> = first
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    let joined = joined.join(" ");
    let msg = joined.strip_prefix("error: ").unwrap_or(&joined);
    format!("{msg} (see topoplex --help)")
}

/// The message for a failed write to stdout (closed pipe, full disk).
fn output_error(e: std::io::Error) -> String {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        return BROKEN_PIPE.to_string();
    }
    format!("writing output: {e}")
}

/// Writes `text` to stdout and flushes, reporting a closed pipe or a full disk as an error.
fn print(text: &str) -> Result<(), String> {
    let mut w = std::io::stdout().lock();
    w.write_all(text.as_bytes())
        .and_then(|()| w.flush())
        .map_err(output_error)
}

/// Reads and normalises `file` under the `--max-simplices` budget (a `.tpx` gives its saved
/// complex).
fn load(file: &Path) -> Result<Complex, String> {
    if let Some(options) = triangulating(file) {
        return Complex::from_path_options(file, budget(), options).map_err(|e| e.to_string());
    }
    topoplex::store::open_complex_with(file, budget(), verifying()).map_err(|e| e.to_string())
}

/// The structure of `kind` for `file`: a saved one is mapped, not rebuilt.
fn load_structure(file: &Path, kind: StructureKind) -> Result<Box<dyn Topology>, String> {
    if triangulating(file).is_some() {
        return topoplex::build(kind, &load(file)?).map_err(|e| e.to_string());
    }
    topoplex::store::open_structure_with(file, kind, budget(), verifying())
        .map_err(|e| e.to_string())
}

/// The read options of `--triangulate` for a mesh input (a saved file holds a complex already).
fn triangulating(file: &Path) -> Option<topoplex::io::ReadOptions> {
    (TRIANGULATE.load(std::sync::atomic::Ordering::Relaxed)
        && !topoplex::store::is_saved_path(file))
    .then_some(topoplex::io::ReadOptions { triangulate: true })
}

fn verifying() -> bool {
    VERIFY.load(std::sync::atomic::Ordering::Relaxed)
}

fn budget() -> Budget {
    Budget {
        max_simplices: *BUDGET.lock().unwrap_or_else(|e| e.into_inner()),
    }
}

fn parse_kind(structure: &str) -> Result<StructureKind, String> {
    // Case-insensitive, as --format is.
    StructureKind::from_name(&structure.to_ascii_lowercase()).ok_or_else(|| {
        let names: Vec<&str> = StructureKind::NAMED.iter().map(|k| k.name()).collect();
        format!(
            "unknown structure `{}` (expected one of: {})",
            echo(structure),
            names.join(", ")
        )
    })
}

fn save(file: &Path, structure: Option<&str>, out: &Path, data: &DropData) -> Result<(), String> {
    // The live complex (`iastar`) is saved too, to be opened back editable.
    let kind = structure.map(parse_kind).transpose()?;
    // Writing over the input would truncate it under its own memory map (a .tpx input).
    not_the_input(file, out, "--out ")?;
    let mut complex = load(file)?;
    data.apply(&mut complex)?;
    let built = match kind {
        Some(k) if topoplex::store::is_saved_path(file) => Some(load_structure(file, k)?),
        Some(k) => Some(topoplex::build(k, &complex).map_err(|e| e.to_string())?),
        None => None,
    };
    topoplex::store::save(out, &complex, built.as_deref()).map_err(|e| e.to_string())
}

fn verify(file: &Path) -> Result<(), String> {
    let saved = Saved::open(file).map_err(|e| e.to_string())?;
    saved.verify().map_err(|e| e.to_string())?;
    let what = saved
        .kind()
        .map_or("complex".to_string(), |k| format!("complex and {k}"));
    print(&format!(
        "{}: {what}: {} bytes verified\n",
        file.display(),
        saved.len()
    ))
}

/// A progress bar on stderr that appears only on a terminal and only once the work has taken
/// about a second (quick reports print nothing there).
struct Progress {
    bar: ProgressBar,
    watcher: Option<(mpsc::Sender<()>, std::thread::JoinHandle<()>)>,
}

impl Progress {
    fn new(steps: u64) -> Progress {
        let bar = ProgressBar::with_draw_target(Some(steps), ProgressDrawTarget::hidden());
        if let Ok(style) =
            ProgressStyle::with_template("{spinner} [{elapsed}] {bar:30} {pos}/{len} {wide_msg}")
        {
            bar.set_style(style);
        }
        let watcher = std::io::stderr().is_terminal().then(|| {
            let (tx, rx) = mpsc::channel::<()>();
            let shown = bar.clone();
            let handle = std::thread::spawn(move || {
                // Dropping the sender (work done) ends the wait early: nothing is drawn.
                if let Err(mpsc::RecvTimeoutError::Timeout) =
                    rx.recv_timeout(Duration::from_secs(1))
                {
                    shown.set_draw_target(ProgressDrawTarget::stderr());
                    shown.enable_steady_tick(Duration::from_millis(120));
                }
            });
            (tx, handle)
        });
        Progress { bar, watcher }
    }

    fn finish(mut self) {
        if let Some((tx, handle)) = self.watcher.take() {
            drop(tx);
            let _ = handle.join();
        }
        self.bar.finish_and_clear();
    }
}

fn report(files: &[PathBuf], json: bool, csv: bool, svg: Option<&Path>) -> Result<(), String> {
    use topoplex_cli::report::{Dataset, render};
    // Per dataset: reading, the census, and each structure's build and four families.
    let per_file = 2 + 5 * StructureKind::NAMED.len() as u64;
    let progress = Progress::new(per_file * files.len().max(1) as u64);
    let mut datasets = Vec::new();
    let run = |name: &str, file: Option<&str>, complex: &Complex| {
        let bar = &progress.bar;
        bar.inc(1);
        let mut step = |what: &str| {
            bar.set_message(format!("{name}: {what}"));
            bar.inc(1);
        };
        Dataset::measure(name, file, complex, &mut step).map_err(|bytes| {
            let name = topoplex::error::echo(name);
            format!("{name}: out of memory: cannot reserve {bytes} bytes for the census's closure")
        })
    };
    if files.is_empty() {
        match run("built-in example", None, &fixtures::builtin_example()) {
            Ok(d) => datasets.push(d),
            Err(e) => {
                progress.finish();
                return Err(e);
            }
        }
    }
    for (i, f) in files.iter().enumerate() {
        let name = f.display().to_string();
        progress.bar.set_message(format!("{name}: reading"));
        let complex = match load(f) {
            Ok(c) => c,
            Err(e) => {
                progress.finish();
                return Err(e);
            }
        };
        match run(&name, Some(&name), &complex) {
            Ok(d) => datasets.push(d),
            Err(e) => {
                progress.finish();
                return Err(e);
            }
        }
        // Unsupported structures skip their timing steps: keep the bar in step per file.
        progress.bar.set_position((i as u64 + 1) * per_file);
    }
    progress.finish();
    if let Some(path) = svg {
        topoplex::io::check_output(path)
            .and_then(|()| std::fs::write(path, topoplex_cli::report::svg::svg(&datasets)))
            .map_err(|e| format!("{}: cannot write: {e}", echo_path(path)))?;
    }
    let text = if json {
        render::json(&datasets)
    } else if csv {
        render::csv(&datasets)
    } else {
        render::markdown(&datasets)
    };
    print(&text)
}

/// The output format called `name`, or a usage error listing the names.
fn output_format(name: &str) -> Result<Format, String> {
    Format::from_name(name).ok_or_else(|| {
        let names: Vec<&str> = Format::ALL.iter().map(|f| f.name()).collect();
        format!(
            "unknown format `{name}` (expected one of: {})",
            names.join(", ")
        )
    })
}

fn convert(
    input: &Path,
    output: &Path,
    format: Option<&str>,
    census: bool,
    round_f32: bool,
    data: &DropData,
) -> Result<(), String> {
    let format = format.map(output_format).transpose()?;
    if census && Format::from_path(output) != Some(Format::Vtk) {
        return Err(format!(
            "--census writes legacy VTK: {} must end in .vtk",
            echo_path(output)
        ));
    }
    // The input's content beyond the complex (OBJ normals, PLY properties, ...) would be lost.
    not_the_input(input, output, "")?;
    let mut complex = load(input)?;
    data.apply(&mut complex)?;
    if census {
        refuse_data(&complex, "convert --census")?;
        return topoplex_cli::report::census_vtk::write_census_vtk(&complex, output)
            .map_err(|e| e.to_string());
    }
    if round_f32 {
        round_coords_to_f32(&mut complex, input)?;
    }
    topoplex::io::write::write_complex(&complex, output, format).map_err(|e| e.to_string())
}

/// `convert --round-f32`: every coordinate to the nearest 32-bit float; one beyond that range
/// (it would become infinite) is refused, naming the vertex.
fn round_coords_to_f32(complex: &mut topoplex::Complex, input: &Path) -> Result<(), String> {
    let Some(c) = complex.coords() else {
        return Ok(());
    };
    let dim = c.dim;
    let mut data = Vec::with_capacity(c.data.len());
    for (i, &x) in c.data.iter().enumerate() {
        let r = x as f32;
        if x.is_finite() && !r.is_finite() {
            return Err(format!(
                "{}: --round-f32: vertex {} coordinate {} = {x:e} is beyond the 32-bit float range",
                echo_path(input),
                i / dim,
                i % dim
            ));
        }
        data.push(f64::from(r));
    }
    complex.set_coords(dim, &data).map_err(|e| e.to_string())
}

fn decompose(
    file: &Path,
    out: &Path,
    force: bool,
    format: Option<&str>,
    data: &DropData,
) -> Result<(), String> {
    let format = format.map(output_format).transpose()?;
    let mut complex = load(file)?;
    data.apply(&mut complex)?;

    prepare_out_dir(file, out, force)?;
    let iqm = topoplex::structures::iqm::Iqm::build(&complex).map_err(|e| e.to_string())?;
    let dec = iqm.decomposition();
    let paths = topoplex::decompose::write_components_of(&dec, &complex, out, format)
        .map_err(|e| e.to_string())?;
    print(&format!(
        "{} components, {} split vertices ({} vertex copies in all); wrote {} files to {}\n",
        dec.components.len(),
        dec.split_vertices.len(),
        dec.copy_vertex.len(),
        paths.len(),
        echo_path(out)
    ))
}

/// `decompose`'s output directory: missing or empty is fine; otherwise `--force` is needed, and
/// then an earlier decomposition's files are deleted (so none is left stale) — unless one of
/// them is the input, which is never overwritten or deleted.
fn prepare_out_dir(input: &Path, out: &Path, force: bool) -> Result<(), String> {
    let at = |e: std::io::Error| format!("--out {}: {e}", echo_path(out));
    let entries = match std::fs::read_dir(out) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(at(e)),
    };
    let input_meta = std::fs::metadata(input).map_err(|e| format!("{}: {e}", echo_path(input)))?;
    let (mut earlier, mut others) = (Vec::new(), 0usize);
    for entry in entries {
        let path = entry.map_err(at)?.path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if topoplex::decompose::is_decomposition_file(name) {
            if std::fs::metadata(&path).is_ok_and(|m| same_file(&m, &input_meta)) {
                return Err(format!(
                    "--out {}: the input {} would be overwritten (decompose never overwrites its input; choose another directory)",
                    echo_path(out),
                    echo_path(input)
                ));
            }
            earlier.push(path);
        } else {
            others += 1;
        }
    }
    if earlier.is_empty() && others == 0 {
        return Ok(());
    }
    if !force {
        return Err(format!(
            "--out {}: directory is not empty; pass --force to replace an earlier decomposition there",
            echo_path(out)
        ));
    }
    for path in earlier {
        std::fs::remove_file(&path)
            .map_err(|e| format!("{}: cannot delete: {e}", echo_path(&path)))?;
    }
    Ok(())
}

/// Whether two paths' metadata are one file (hard links and symbolic links included).
/// Refuses an output path that is the input file itself (issue 16 class 9: never overwrite the
/// input); `flag` names the argument in the message.
fn not_the_input(input: &Path, out: &Path, flag: &str) -> Result<(), String> {
    match (std::fs::metadata(input), std::fs::metadata(out)) {
        (Ok(a), Ok(b)) if same_file(&a, &b) => Err(format!(
            "{flag}{} is the input file; choose another path",
            echo_path(out)
        )),
        _ => Ok(()),
    }
}

fn same_file(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        a.dev() == b.dev() && a.ino() == b.ino()
    }
    #[cfg(not(unix))]
    {
        a.len() == b.len()
            && a.modified().ok() == b.modified().ok()
            && a.created().ok() == b.created().ok()
    }
}

fn simplify(
    input: &Path,
    out: &Path,
    (ratio, preserve_topology, keep_regions): (f64, bool, Option<&str>),
    data: &DropData,
) -> Result<(), String> {
    use topoplex::io::write::write_complex;
    use topoplex::simplify::{Options, check_output, simplify_owned};
    if !(ratio > 0.0 && ratio <= 1.0) {
        return Err(format!("--ratio {ratio} is outside (0, 1]"));
    }
    let options = Options {
        ratio,
        preserve_topology,
        keep_regions: keep_regions.map(str::to_string),
    };
    not_the_input(input, out, "--out ")?;
    let mut complex = load(input)?;
    data.apply(&mut complex)?;
    // Refuse an unknown or unfit format and an unwritable output before the work, not after.
    let existed = out.exists();
    check_output(out, &complex).map_err(|e| e.to_string())?;
    let progress = Progress::new(1);
    progress.bar.set_message("contracting edges");
    let result = simplify_owned(complex, &options, &mut |done, total| {
        progress.bar.set_length(total as u64);
        progress.bar.set_position(done as u64);
    });
    progress.finish();
    let written = result.map_err(|e| e.to_string()).and_then(|s| {
        write_complex(&s.complex, out, None)
            .map(|()| s)
            .map_err(|e| e.to_string())
    });
    let s = match written {
        Ok(s) => s,
        Err(e) => {
            if !existed {
                let _ = std::fs::remove_file(out);
            }
            return Err(e);
        }
    };
    let st = s.stats;
    let mut refused = if preserve_topology {
        format!(
            ", {} refused by the link condition ({} retry rounds)",
            st.refused, st.refills
        )
    } else {
        String::new()
    };
    if options.keep_regions.is_some() {
        refused += &format!(", {} refused to keep the regions", st.refused_regions);
    }
    print(&format!(
        "{} -> {} top simplices (target {}), {} contractions{refused}; wrote {}\n",
        st.input_tops,
        st.output_tops,
        st.target_tops,
        st.contractions,
        echo_path(out)
    ))
}

fn dump_relation(
    file: PathBuf,
    structure: &str,
    (p, q): (usize, usize),
    simplex: Option<String>,
) -> Result<(), String> {
    let kind = parse_kind(structure)?;
    let topo = load_structure(&file, kind)?;
    let d = topo.dimension();
    if p > d || q > d {
        return Err(format!(
            "relation R_{{{p},{q}}}: the complex has dimension {d}"
        ));
    }
    let sigmas: Vec<u32> = match simplex {
        Some(text) => {
            let ids = text
                .split_whitespace()
                .map(|t| {
                    t.parse::<u32>()
                        .map_err(|_| format!("--simplex: `{}` is not a vertex id", echo(t)))
                })
                .collect::<Result<Vec<u32>, String>>()?;
            if ids.len() != p + 1 {
                return Err(format!(
                    "--simplex has {} vertices, but P = {p} needs {}",
                    ids.len(),
                    p + 1
                ));
            }
            topoplex::relation::normalize_simplex(&ids, topo.vertex_count())
                .map_err(|e| e.to_string())?
        }
        None => {
            let mut all = Vec::new();
            topoplex::error::caught_quietly(std::panic::AssertUnwindSafe(|| {
                topo.simplices(p, &mut all)
            }))
            .map_err(|_| corrupt_answer(&file))?;
            all
        }
    };
    // A saved file's structure is queried in place, checked only in shape unless --verify:
    // arrays altered behind their checksums may break a query (never a read out of bounds),
    // which is reported as the file's fault, not as a crash.
    let answered = topoplex::error::caught_quietly(std::panic::AssertUnwindSafe(|| {
        write_relation(topo.as_ref(), &sigmas, p, q)
    }));
    answered.unwrap_or_else(|_| Err(corrupt_answer(&file)))
}

/// The message for a query that broke on a saved file's arrays.
fn corrupt_answer(file: &Path) -> String {
    format!(
        "{}: corrupt saved file: inconsistent arrays met while answering (`topoplex verify` names the first)",
        echo_path(file)
    )
}

/// Writes R_{p,q} of every p-simplex of `sigmas` (rows of p + 1 ids) to stdout.
fn write_relation(topo: &dyn Topology, sigmas: &[u32], p: usize, q: usize) -> Result<(), String> {
    let stdout = std::io::stdout();
    let mut w = BufWriter::new(stdout.lock());
    let mut out = Vec::new();
    let mut line = String::new();
    for sigma in sigmas.chunks_exact(p + 1) {
        topo.relation(sigma, q, &mut out)
            .map_err(|e| e.to_string())?;
        sort_rows(&mut out, q + 1);
        line.clear();
        write_ids(&mut line, sigma);
        for tau in out.chunks_exact(q + 1) {
            line.push(';');
            write_ids(&mut line, tau);
        }
        line.push('\n');
        w.write_all(line.as_bytes()).map_err(output_error)?;
    }
    w.flush().map_err(output_error)
}

fn write_ids(line: &mut String, ids: &[u32]) {
    use std::fmt::Write as _;
    for (i, v) in ids.iter().enumerate() {
        if i > 0 {
            line.push(' ');
        }
        let _ = write!(line, "{v}");
    }
}
