//! `topoplex`: report on a complex and dump its relations through any structure.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, Subcommand};
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
    /// Dimension, simplex counts, absorbed input, and every structure's storage and build time.
    Report {
        /// .off, .obj, .mesh or .simplices; without it, a built-in example complex with a wire
        /// edge, a dangling triangle, a tetrahedron and a non-manifold vertex and edge.
        file: Option<PathBuf>,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
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
        Command::Report { file, json } => report(file, json),
        Command::Relation {
            file,
            structure,
            relation,
            simplex,
        } => dump_relation(file, &structure, relation, simplex),
        Command::Decompose { file, out } => decompose(&file, &out),
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

/// A structure's storage, build time in ms and `summary()` figures, or why it was not built.
type Outcome = Result<(topoplex::Storage, f64, Vec<(&'static str, u64)>), String>;

struct Row {
    kind: StructureKind,
    outcome: Outcome,
}

fn report(file: Option<PathBuf>, json: bool) -> Result<(), String> {
    let complex = match &file {
        Some(f) => load(f)?,
        None => fixtures::builtin_example(),
    };
    let counts: Vec<usize> = complex.closure().iter().map(|t| t.len()).collect();
    let total: usize = counts.iter().sum();
    let rows: Vec<Row> = StructureKind::ALL
        .into_iter()
        .map(|kind| {
            let start = Instant::now();
            let outcome = structures::build(kind, &complex)
                .map(|s| {
                    (
                        s.storage(),
                        start.elapsed().as_secs_f64() * 1e3,
                        s.summary(),
                    )
                })
                .map_err(|e| e.to_string());
            Row { kind, outcome }
        })
        .collect();
    let stats = complex.stats();
    if json {
        let mut structs = serde_json::Map::new();
        for r in &rows {
            let v = match &r.outcome {
                Ok((s, ms, extra)) => {
                    let mut v = serde_json::json!({
                        "integers": s.integers, "bits": s.bits, "bytes": s.bytes, "build_ms": ms,
                        "bytes_per_simplex": s.bytes as f64 / total as f64,
                    });
                    for (k, x) in extra {
                        v[*k] = serde_json::json!(x);
                    }
                    v
                }
                Err(reason) => serde_json::json!({ "unsupported": reason }),
            };
            structs.insert(r.kind.name().to_string(), v);
        }
        let out = serde_json::json!({
            "file": file.as_ref().map(|f| f.display().to_string()),
            "dimension": complex.dimension(),
            "vertices": complex.vertex_count(),
            "simplices": counts,
            "top_simplices": complex.top_counts(),
            "input_simplices": stats.input_simplices,
            "absorbed_duplicates": stats.absorbed_duplicates,
            "absorbed_faces": stats.absorbed_faces,
            "structures": structs,
        });
        println!(
            "{}",
            serde_json::to_string_pretty(&out).map_err(|e| e.to_string())?
        );
        return Ok(());
    }
    let name = file
        .as_ref()
        .map_or("built-in example".to_string(), |f| f.display().to_string());
    println!("complex: {name}");
    println!("dimension: {}", complex.dimension());
    println!("simplices per dimension (n_0..n_d): {}", join(&counts));
    println!(
        "top simplices per dimension: {}",
        join(&complex.top_counts())
    );
    println!(
        "input: {} simplices listed, {} absorbed as duplicates, {} absorbed as faces of other listed simplices",
        stats.input_simplices, stats.absorbed_duplicates, stats.absorbed_faces
    );
    println!();
    println!(
        "{:<6} {:>14} {:>12} {:>14} {:>10} {:>10}",
        "struct", "paper ints", "paper bits", "heap bytes", "B/simplex", "build ms"
    );
    for r in &rows {
        match &r.outcome {
            Ok((s, ms, extra)) => {
                let extra: Vec<String> = extra
                    .iter()
                    .map(|(k, x)| format!("{x} {}", k.replace('_', " ")))
                    .collect();
                let line = format!(
                    "{:<6} {:>14} {:>12} {:>14} {:>10.1} {:>10.2}  {}",
                    r.kind.name(),
                    s.integers,
                    s.bits,
                    s.bytes,
                    s.bytes as f64 / total as f64,
                    ms,
                    extra.join(", ")
                );
                println!("{}", line.trim_end());
            }
            Err(reason) => println!("{:<6} unsupported: {reason}", r.kind.name()),
        }
    }
    Ok(())
}

fn decompose(file: &Path, out: &Path) -> Result<(), String> {
    let complex = load(file)?;
    let iqm = topoplex::structures::iqm::Iqm::build(&complex).map_err(|e| e.to_string())?;
    let dec = iqm.decomposition();
    let paths = topoplex::io::write::write_components(&dec, complex.coords(), out)
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

fn join(v: &[usize]) -> String {
    v.iter()
        .map(|x| x.to_string())
        .collect::<Vec<_>>()
        .join(" ")
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
