//! `topoplex`: report on a complex and dump its relations through any structure.

use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::mpsc;
use std::time::Duration;

use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use topoplex::io::write::Format;
use topoplex::relation::sort_rows;
use topoplex::{Complex, StructureKind, fixtures, structures};

#[derive(Parser)]
#[command(
    name = "topoplex",
    version,
    about = "Topological data structures for arbitrary simplicial complexes"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// The survey's comparison tables for each file: census (wire edges, dangling faces, C_e,
    /// C_v − n_0, IQM components, non-manifold simplices), every structure's storage, build time
    /// and time per retrieved element for each relation family (sampled queries).
    Report {
        /// .off, .obj, .mesh or .simplices files; without any, a built-in example complex with
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
        /// ig, sig, ia, iqm, nmia, ts, pe, le, de.
        #[arg(long)]
        structure: String,
        /// P,Q (for example 1,2: the triangles around each edge).
        #[arg(long, value_parser = parse_pq)]
        relation: (usize, usize),
        /// Only this P-simplex, given as vertex ids ("V0 V1 ...").
        #[arg(long)]
        simplex: Option<String>,
    },
    /// Cut the complex into its IQM components (the standard decomposition into initial
    /// quasi-manifolds) and write each as its own file, plus gluing.json mapping every
    /// component's local vertex ids back to the original ids.
    Decompose {
        file: PathBuf,
        /// Output directory (created if missing).
        #[arg(long)]
        out: PathBuf,
        /// Write every component in this format (off, obj, mesh, simplices) instead of by
        /// dimension; refused, writing nothing, if it cannot hold a component.
        #[arg(long)]
        format: Option<String>,
    },
    /// Read INPUT and write it to OUTPUT (formats by extension): the top simplices in input
    /// order and winding, isolated vertices and wire edges kept, coordinates bit for bit. A
    /// format that cannot hold the complex is refused with the reason.
    Convert {
        input: PathBuf,
        output: PathBuf,
        /// Output format (off, obj, mesh, simplices) instead of OUTPUT's extension.
        #[arg(long)]
        format: Option<String>,
    },
    /// Quadric-error edge-contraction simplification (Garland–Heckbert, any dimension) down to
    /// about RATIO × the input's top simplices; the output format follows its extension (.off,
    /// .obj, .mesh, .simplices).
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
    },
}

fn parse_pq(s: &str) -> Result<(usize, usize), String> {
    let (p, q) = s.split_once(',').ok_or("expected P,Q such as 1,2")?;
    let num = |t: &str| {
        t.trim()
            .parse::<usize>()
            .map_err(|_| format!("`{t}` is not a dimension"))
    };
    Ok((num(p)?, num(q)?))
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
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
        Command::Decompose { file, out, format } => decompose(&file, &out, format.as_deref()),
        Command::Convert {
            input,
            output,
            format,
        } => convert(&input, &output, format.as_deref()),
        Command::Simplify {
            input,
            out,
            ratio,
            preserve_topology,
        } => simplify(&input, &out, ratio, preserve_topology),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(msg) => {
            eprintln!("topoplex: {msg}");
            ExitCode::FAILURE
        }
    }
}

fn load(file: &Path) -> Result<Complex, String> {
    Complex::from_path(file).map_err(|e| e.to_string())
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
    use topoplex::report::{Dataset, render};
    // Per dataset: reading, the census, and each structure's build and four families.
    let per_file = 2 + 5 * StructureKind::ALL.len() as u64;
    let progress = Progress::new(per_file * files.len().max(1) as u64);
    let mut datasets = Vec::new();
    let run = |name: &str, file: Option<&str>, complex: &Complex| {
        let bar = &progress.bar;
        bar.inc(1);
        let mut step = |what: &str| {
            bar.set_message(format!("{name}: {what}"));
            bar.inc(1);
        };
        Dataset::measure(name, file, complex, &mut step)
    };
    if files.is_empty() {
        datasets.push(run("built-in example", None, &fixtures::builtin_example()));
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
        datasets.push(run(&name, Some(&name), &complex));
        // Unsupported structures skip their timing steps: keep the bar in step per file.
        progress.bar.set_position((i as u64 + 1) * per_file);
    }
    progress.finish();
    if let Some(path) = svg {
        std::fs::write(path, topoplex::report::svg::svg(&datasets))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    let text = if json {
        render::json(&datasets)
    } else if csv {
        render::csv(&datasets)
    } else {
        render::markdown(&datasets)
    };
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    w.write_all(text.as_bytes())
        .and_then(|()| w.flush())
        .map_err(|e| format!("writing output: {e}"))
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

fn convert(input: &Path, output: &Path, format: Option<&str>) -> Result<(), String> {
    let format = format.map(output_format).transpose()?;
    let complex = load(input)?;
    topoplex::io::write::write_complex(&complex, output, format).map_err(|e| e.to_string())
}

fn decompose(file: &Path, out: &Path, format: Option<&str>) -> Result<(), String> {
    let format = format.map(output_format).transpose()?;
    let complex = load(file)?;
    let iqm = topoplex::structures::iqm::Iqm::build(&complex).map_err(|e| e.to_string())?;
    let dec = iqm.decomposition();
    let paths = match format {
        None => topoplex::io::write::write_components(&dec, complex.coords(), out),
        Some(f) => topoplex::io::write::write_components_as(&dec, complex.coords(), out, f),
    }
    .map_err(|e| e.to_string())?;
    println!(
        "{} components, {} split vertices ({} vertex copies in all); wrote {} files to {}",
        dec.components.len(),
        dec.split_vertices.len(),
        dec.copy_vertex.len(),
        paths.len(),
        out.display()
    );
    Ok(())
}

fn simplify(input: &Path, out: &Path, ratio: f64, preserve_topology: bool) -> Result<(), String> {
    use topoplex::io::write::write_complex;
    use topoplex::simplify::{Options, check_output, simplify_owned};
    let options = Options {
        ratio,
        preserve_topology,
    };
    if !(ratio > 0.0 && ratio <= 1.0) {
        return Err(format!("--ratio {ratio} is outside (0, 1]"));
    }
    let complex = load(input)?;
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
    match written {
        Ok(s) => {
            let st = s.stats;
            println!(
                "{} -> {} top simplices (target {}), {} contractions{}; wrote {}",
                st.input_tops,
                st.output_tops,
                st.target_tops,
                st.contractions,
                if preserve_topology {
                    format!(
                        ", {} refused by the link condition ({} retry rounds)",
                        st.refused, st.refills
                    )
                } else {
                    String::new()
                },
                out.display()
            );
            Ok(())
        }
        Err(e) => {
            if !existed {
                let _ = std::fs::remove_file(out);
            }
            Err(e)
        }
    }
}

fn dump_relation(
    file: PathBuf,
    structure: &str,
    (p, q): (usize, usize),
    simplex: Option<String>,
) -> Result<(), String> {
    let kind = StructureKind::from_name(structure).ok_or_else(|| {
        let names: Vec<&str> = StructureKind::ALL.iter().map(|k| k.name()).collect();
        format!(
            "unknown structure `{structure}` (expected one of: {})",
            names.join(", ")
        )
    })?;
    let complex = load(&file)?;
    let topo = structures::build(kind, &complex).map_err(|e| e.to_string())?;
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
                        .map_err(|_| format!("--simplex: `{t}` is not a vertex id"))
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
            topo.simplices(p, &mut all);
            all
        }
    };
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
        w.write_all(line.as_bytes())
            .map_err(|e| format!("writing output: {e}"))?;
    }
    w.flush().map_err(|e| format!("writing output: {e}"))
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
