//! Text forms of a report: Markdown tables, one JSON document, one CSV table.

use std::fmt::Write as _;

use serde_json::{Value, json};

use super::census::Census;
use super::timing::{Family, Measured, StructureResult};
use super::{Dataset, timing};

fn join<T: ToString>(v: &[T]) -> String {
    v.iter()
        .map(|x| x.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

fn iqm_text(d: &Dataset) -> String {
    match &d.census.iqm_components {
        Ok(n) => n.to_string(),
        Err(_) => "—".to_string(),
    }
}

/// A Markdown table cell: no pipe or line break inside.
fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

fn ns(x: Option<f64>) -> String {
    match x {
        Some(v) if v >= 100.0 => format!("{v:.0}"),
        Some(v) => format!("{v:.1}"),
        None => "—".to_string(),
    }
}

fn family(m: &Measured, f: Family) -> Option<&timing::FamilyTiming> {
    m.families.iter().find(|t| t.family == f)
}

/// The sampling sentence shown under each dataset.
pub fn sample_text(d: &Dataset) -> String {
    let s = &d.sample;
    format!(
        "queried {} of {} vertices and {} of {} top simplices of dimension ≥ 1 (evenly spread)",
        s.vertices, s.vertices_total, s.tops, s.tops_total
    )
}

/// Markdown: a census table over all datasets, a bytes-per-simplex table over all datasets,
/// then per dataset a table of every structure's storage and times.
pub fn markdown(datasets: &[Dataset]) -> String {
    let mut s = String::new();
    preamble(&mut s);
    census_table(&mut s, datasets);
    storage_table(&mut s, datasets);
    for d in datasets {
        dataset_section(&mut s, d);
    }
    s
}

/// The title and how the report was made.
fn preamble(s: &mut String) {
    let _ = writeln!(s, "# Topoplex report\n");
    let _ = writeln!(
        s,
        "Census definitions, relation families and how times are taken: the README's CLI \
         section and the `topoplex_cli::report` module documentation. Times are per retrieved element (one simplex of an answer); \
         at most {} vertices and {} top simplices are queried per dataset, each measurement \
         repeated for at least {} ms after a warm-up pass.\n",
        timing::SAMPLE,
        timing::SAMPLE,
        timing::MIN_TIME.as_millis()
    );
}

/// The census of every dataset, a row each, and the columns' legend.
fn census_table(s: &mut String, datasets: &[Dataset]) {
    let _ = writeln!(s, "## Census\n");
    let _ = writeln!(
        s,
        "| dataset | d | V | WE | DF | top simplices (dim 0..d) | C_e | C_v − n_0 | IQM components | non-manifold (dim 0..d) |"
    );
    let _ = writeln!(s, "|---|--:|--:|--:|--:|---|--:|--:|--:|---|");
    for d in datasets {
        let c = &d.census;
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {}{} |",
            cell(&d.name),
            c.dimension,
            c.vertices,
            c.wire_edges,
            c.dangling_faces,
            join(&c.top_simplices),
            c.c_e,
            c.c_v_minus_n0,
            iqm_text(d),
            join(&c.non_manifold),
            link_notes(c)
        );
    }
    let _ = writeln!(
        s,
        "\nd: dimension; V: vertices; WE: wire edges (top edges); DF: dangling faces (top \
         triangles when d ≥ 3); C_e: link components summed over non-manifold edges; C_v: link \
         components summed over vertices; non-manifold: simplices whose link is neither a sphere \
         nor a ball."
    );
}

/// The attributes of a dataset, a line each: name, where, type × components, and for labels
/// the distinct values with their counts (the first 12; `report --json` gives all).
fn attribute_lines(s: &mut String, d: &Dataset) {
    if d.attributes.is_empty() {
        let _ = writeln!(s, "- attributes: none");
        return;
    }
    let _ = writeln!(s, "- attributes:");
    for a in &d.attributes {
        let mut labels: Vec<String> = a
            .labels
            .iter()
            .take(12)
            .map(|l| {
                let names = if l.names.is_empty() {
                    String::new()
                } else {
                    format!(" \"{}\"", l.names.join("\" / \""))
                };
                format!("{}{names}: {}", l.label, l.count)
            })
            .collect();
        if a.labels.len() > 12 {
            labels.push(format!("... ({} distinct)", a.labels.len()));
        }
        let labels = if labels.is_empty() {
            String::new()
        } else {
            format!("; labels {}", labels.join(", "))
        };
        let _ = writeln!(
            s,
            "  - `{}` on {} {}, {} × {}{labels}",
            cell(&a.name),
            a.elements,
            a.on,
            a.value_type,
            a.components
        );
    }
}

/// What follows a census's non-manifold counts: the links approximated, and those left
/// unclassified with the first of them.
fn link_notes(c: &Census) -> String {
    let mut notes = if c.approximated_links > 0 {
        format!(" (≥; {} links approximated)", c.approximated_links)
    } else {
        String::new()
    };
    if c.unclassified_links > 0 {
        let shown: Vec<String> = c
            .unclassified_examples
            .iter()
            .map(|s| format!("[{}]", join(s)))
            .collect();
        let more = if c.unclassified_links > shown.len() {
            ", ..."
        } else {
            ""
        };
        let _ = write!(
            notes,
            " ({} links unclassified, over the work budget: {}{more})",
            c.unclassified_links,
            shown.join(" ")
        );
    }
    notes
}

/// Heap bytes per simplex of every structure, a row per dataset.
fn storage_table(s: &mut String, datasets: &[Dataset]) {
    let _ = writeln!(s, "\n## Storage: heap bytes per simplex\n");
    let kinds: Vec<&str> = datasets
        .first()
        .map(|d| d.structures.iter().map(|r| r.kind.name()).collect())
        .unwrap_or_default();
    let _ = writeln!(s, "| dataset | simplices | {} |", kinds.join(" | "));
    let _ = writeln!(s, "|---|--:|{}", "--:|".repeat(kinds.len()));
    for d in datasets {
        let total: usize = d.census.simplices.iter().sum();
        let cells: Vec<String> = d
            .structures
            .iter()
            .map(|r| match &r.outcome {
                Ok(m) => format!("{:.1}", m.bytes_per_simplex),
                Err(_) => "—".to_string(),
            })
            .collect();
        let _ = writeln!(
            s,
            "| {} | {} | {} |",
            cell(&d.name),
            total,
            cells.join(" | ")
        );
    }
}

/// One dataset: its counts and input, then a row per structure.
fn dataset_section(s: &mut String, d: &Dataset) {
    let c = &d.census;
    let _ = writeln!(s, "\n## {}\n", d.name);
    let _ = writeln!(s, "- dimension: {}", c.dimension);
    let _ = writeln!(
        s,
        "- simplices per dimension (n_0..n_d): {}",
        join(&c.simplices)
    );
    let _ = writeln!(
        s,
        "- top simplices per dimension: {}",
        join(&c.top_simplices)
    );
    let _ = writeln!(
        s,
        "- input: {} simplices listed, {} absorbed as duplicates, {} absorbed as faces of other listed simplices",
        d.input.input_simplices, d.input.absorbed_duplicates, d.input.absorbed_faces
    );
    if let Err(e) = &c.iqm_components {
        let _ = writeln!(s, "- IQM decomposition: {e}");
    }
    attribute_lines(s, d);
    let _ = writeln!(s, "- timing sample: {}\n", sample_text(d));
    let _ = writeln!(
        s,
        "| structure | paper ints | paper bits | heap bytes | B/simplex | build ms | boundary ns | co-boundary ns | adj. vertex ns | adj. top ns | notes |"
    );
    let _ = writeln!(s, "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|---|");
    for r in &d.structures {
        structure_row(s, r);
    }
}

/// A structure's storage, build time and query times, or why it cannot encode the dataset.
fn structure_row(s: &mut String, r: &StructureResult) {
    let m = match &r.outcome {
        Ok(m) => m,
        Err(reason) => {
            let _ = writeln!(
                s,
                "| {} | — | — | — | — | — | — | — | — | — | unsupported: {} |",
                r.kind.name(),
                cell(reason)
            );
            return;
        }
    };
    let times: Vec<String> = Family::ALL
        .iter()
        .map(|&f| {
            family(m, f).map_or("—".into(), |t| match &t.error {
                Some(_) => "error".into(),
                None => ns(t.ns_per_element),
            })
        })
        .collect();
    let mut notes: Vec<String> = m
        .summary
        .iter()
        .map(|(k, v)| format!("{v} {}", k.replace('_', " ")))
        .collect();
    notes.extend(m.families.iter().filter_map(|t| {
        t.error
            .as_ref()
            .map(|e| format!("{} query failed: {e}", t.family.name()))
    }));
    let _ = writeln!(
        s,
        "| {} | {} | {} | {} | {:.1} | {:.3} | {} | {} |",
        r.kind.name(),
        m.storage.integers,
        m.storage.bits,
        m.storage.bytes,
        m.bytes_per_simplex,
        m.build_ms,
        times.join(" | "),
        cell(&notes.join(", "))
    );
}

/// One dataset as a JSON object. The fields of the first `report --json` (file, dimension,
/// vertices, simplices, top_simplices, input_simplices, absorbed_*, and per structure
/// integers, bits, bytes, build_ms, bytes_per_simplex, summary figures or `unsupported`) are
/// kept; `census`, `sample` and per structure `families` are added.
pub fn json_value(d: &Dataset) -> Value {
    let c = &d.census;
    let mut structs = serde_json::Map::new();
    for r in &d.structures {
        let v = match &r.outcome {
            Ok(m) => {
                let mut v = json!({
                    "integers": m.storage.integers,
                    "bits": m.storage.bits,
                    "bytes": m.storage.bytes,
                    "bytes_per_simplex": m.bytes_per_simplex,
                    "build_ms": m.build_ms,
                    "build_ns_per_simplex": m.build_ns_per_simplex,
                    "builds": m.builds,
                });
                for (k, x) in &m.summary {
                    v[k.as_str()] = json!(x);
                }
                let mut fams = serde_json::Map::new();
                for t in &m.families {
                    fams.insert(t.family.name().to_string(), json!(t));
                }
                v["families"] = Value::Object(fams);
                v
            }
            Err(reason) => json!({ "unsupported": reason }),
        };
        structs.insert(r.kind.name().to_string(), v);
    }
    let mut census = json!({
        "wire_edges": c.wire_edges,
        "dangling_faces": c.dangling_faces,
        "c_e": c.c_e,
        "c_v": c.c_v,
        "c_v_minus_n0": c.c_v_minus_n0,
        "iqm_components": c.iqm_components.as_ref().ok(),
        "non_manifold": c.non_manifold,
        "approximated_links": c.approximated_links,
        "unclassified_links": c.unclassified_links,
        "unclassified_examples": c.unclassified_examples,
    });
    if let Err(e) = &c.iqm_components {
        census["iqm_error"] = json!(e);
    }
    json!({
        "file": d.file,
        "name": d.name,
        "dimension": c.dimension,
        "vertices": c.vertices,
        "simplices": c.simplices,
        "top_simplices": c.top_simplices,
        "input_simplices": d.input.input_simplices,
        "absorbed_duplicates": d.input.absorbed_duplicates,
        "absorbed_faces": d.input.absorbed_faces,
        "census": census,
        "sample": d.sample,
        "structures": structs,
        "attributes": d.attributes,
    })
}

/// JSON: the dataset's object for one dataset (as the first `report --json` printed), an array
/// of them for several.
pub fn json(datasets: &[Dataset]) -> String {
    let v = match datasets {
        [one] => json_value(one),
        many => Value::Array(many.iter().map(json_value).collect()),
    };
    serde_json::to_string_pretty(&v).expect("JSON of numbers and strings") + "\n"
}

/// The CSV columns, in order.
pub const CSV_COLUMNS: [&str; 25] = [
    "dataset",
    "dimension",
    "vertices",
    "simplices",
    "top_simplices",
    "wire_edges",
    "dangling_faces",
    "c_e",
    "c_v_minus_n0",
    "iqm_components",
    "non_manifold",
    "structure",
    "paper_integers",
    "paper_bits",
    "heap_bytes",
    "bytes_per_simplex",
    "build_ms",
    "build_ns_per_simplex",
    "boundary_ns_per_element",
    "coboundary_ns_per_element",
    "adjacency_vertex_ns_per_element",
    "adjacency_top_ns_per_element",
    "sampled_vertices",
    "sampled_tops",
    "unsupported",
];

/// RFC 4180 field: quoted when it holds a comma, a quote or a line break.
fn field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// CSV: one row per dataset and structure (the census repeated on each of a dataset's rows;
/// lists as space-separated numbers; empty cells where a figure does not apply).
pub fn csv(datasets: &[Dataset]) -> String {
    let mut s = CSV_COLUMNS.join(",") + "\n";
    let opt = |x: Option<f64>| x.map_or(String::new(), |v| format!("{v:.3}"));
    for d in datasets {
        let c = &d.census;
        for r in &d.structures {
            let mut row: Vec<String> = vec![
                field(&d.name),
                c.dimension.to_string(),
                c.vertices.to_string(),
                join(&c.simplices),
                join(&c.top_simplices),
                c.wire_edges.to_string(),
                c.dangling_faces.to_string(),
                c.c_e.to_string(),
                c.c_v_minus_n0.to_string(),
                c.iqm_components
                    .as_ref()
                    .map_or(String::new(), |n| n.to_string()),
                join(&c.non_manifold),
                r.kind.name().to_string(),
            ];
            match &r.outcome {
                Ok(m) => {
                    row.extend([
                        m.storage.integers.to_string(),
                        m.storage.bits.to_string(),
                        m.storage.bytes.to_string(),
                        format!("{:.3}", m.bytes_per_simplex),
                        format!("{:.4}", m.build_ms),
                        format!("{:.2}", m.build_ns_per_simplex),
                    ]);
                    row.extend(
                        Family::ALL
                            .iter()
                            .map(|&f| opt(family(m, f).and_then(|t| t.ns_per_element))),
                    );
                    row.extend([
                        d.sample.vertices.to_string(),
                        d.sample.tops.to_string(),
                        String::new(),
                    ]);
                }
                Err(reason) => {
                    row.extend(std::iter::repeat_n(String::new(), 10));
                    row.extend([
                        d.sample.vertices.to_string(),
                        d.sample.tops.to_string(),
                        field(reason),
                    ]);
                }
            }
            debug_assert_eq!(row.len(), CSV_COLUMNS.len());
            s += &row.join(",");
            s.push('\n');
        }
    }
    s
}
