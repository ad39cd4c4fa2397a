//! The bad-input catalogue: every class of bad file tried on every reader, with the exact error
//! it gets. `docs/bad-input.md` holds the generated table; this test fails when the table is
//! stale (regenerate: `TOPOPLEX_WRITE_BAD_INPUT_DOC=1 cargo test --test it bad_input::`).

use crate::common;

use std::path::PathBuf;

use topoplex::Complex;

/// (class, file name, content): the file name's extension picks the reader.
fn cases() -> Vec<(&'static str, &'static str, Vec<u8>)> {
    let t = |s: &str| s.as_bytes().to_vec();
    let mut big = String::from("s");
    for i in 0..17 {
        big.push_str(&format!(" {i}"));
    }
    let mut cases = vec![
        ("empty file", "empty.off", t("")),
        ("empty file", "empty.obj", t("")),
        ("empty file", "empty.mesh", t("")),
        ("empty file", "empty.simplices", t("# nothing\n")),
        (
            "truncated file",
            "truncated.off",
            t("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1"),
        ),
        (
            "truncated file",
            "truncated.mesh",
            t("MeshVersionFormatted 2\nDimension 3\nVertices\n3\n0 0 0 1\n1 0 0 1\n"),
        ),
        (
            "truncated file",
            "truncated.obj",
            t("v 0 0 0\nv 1 0 0\nf 1 2 \\\n"),
        ),
        ("wrong header", "header.off", t("OFX\n3 1 0\n")),
        (
            "wrong header",
            "header.mesh",
            t("Dimension 3\nVertices\n0\n"),
        ),
        ("binary OFF", "binary.off", t("OFF BINARY\n")),
        ("unknown statement", "unknown.obj", t("v 0 0 0\nq 1 2\n")),
        (
            "unknown section",
            "unknown.mesh",
            t("MeshVersionFormatted 2\nDimension 3\nPrisms\n0\n"),
        ),
        ("unknown line", "unknown.simplices", t("s 0 1\nt 1 2\n")),
        (
            "counts disagree with content",
            "fewer-faces.off",
            t("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
        ),
        (
            "counts disagree with content",
            "extra.off",
            t("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n"),
        ),
        (
            "counts disagree with content",
            "fewer.mesh",
            t(
                "MeshVersionFormatted 2\nDimension 3\nVertices\n3\n0 0 0 1\n1 0 0 1\n0 1 0 1\nTriangles\n2\n1 2 3 0\nEnd\n",
            ),
        ),
        (
            "count far larger than the file",
            "huge.off",
            t("OFF\n4000000000 1 0\n0 0 0\n"),
        ),
        (
            "count far larger than the file",
            "huge.mesh",
            t("MeshVersionFormatted 2\nDimension 3\nVertices\n4000000000\n0 0 0 1\n"),
        ),
        (
            "count above 32 bits",
            "overflow-count.off",
            t("OFF\n99999999999 1 0\n"),
        ),
        (
            "non-numeric number",
            "word.off",
            t("OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"),
        ),
        ("non-numeric id", "word.simplices", t("s 0 one\n")),
        (
            "overflowing id",
            "overflow.simplices",
            t("s 0 99999999999\n"),
        ),
        (
            "negative id",
            "negative.off",
            t("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"),
        ),
        ("negative id", "negative.simplices", t("s 0 -2\n")),
        (
            "index 0 in a 1-based format",
            "zero.obj",
            t("v 0 0 0\nv 1 0 0\nl 0 1\n"),
        ),
        (
            "relative index before the first vertex",
            "relative.obj",
            t("v 0 0 0\nl -1 -2\n"),
        ),
        (
            "out-of-range vertex id",
            "range.off",
            t("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n"),
        ),
        (
            "out-of-range vertex id",
            "range.obj",
            t("v 0 0 0\nv 1 0 0\nf 1 2 3\n"),
        ),
        (
            "out-of-range vertex id",
            "range.mesh",
            t(
                "MeshVersionFormatted 2\nDimension 3\nVertices\n2\n0 0 0 1\n1 0 0 1\nEdges\n1\n1 3 0\n",
            ),
        ),
        (
            "out-of-range vertex id",
            "range.simplices",
            t("v 0\nv 1\ns 0 2\n"),
        ),
        (
            "repeated vertex in a simplex",
            "repeat.off",
            t("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 1\n"),
        ),
        (
            "repeated vertex in a simplex",
            "repeat.obj",
            t("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -2\n"),
        ),
        (
            "repeated vertex in a simplex",
            "repeat.mesh",
            t(
                "MeshVersionFormatted 2\nDimension 3\nVertices\n3\n0 0 0 1\n1 0 0 1\n0 1 0 1\nTriangles\n1\n1 2 2 0\n",
            ),
        ),
        (
            "repeated vertex in a simplex",
            "repeat.simplices",
            t("s 4 2 4\n"),
        ),
        (
            "polygon that is not a simplex",
            "quad.off",
            t("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n"),
        ),
        (
            "polygon that is not a simplex",
            "quad.obj",
            t("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"),
        ),
        (
            "polygon that is not a simplex",
            "quad.mesh",
            t(
                "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n1 1 0 1\n0 1 0 1\nQuadrilaterals\n1\n1 2 3 4 0\n",
            ),
        ),
        (
            "face with 0 vertices",
            "zero-face.off",
            t("OFF\n1 1 0\n0 0 0\n0\n"),
        ),
        (
            "inconsistent coordinate count",
            "coords.simplices",
            t("v 0 0\nv 1\ns 0 1\n"),
        ),
        (
            "dimension above the maximum (15)",
            "dim16.simplices",
            big.into_bytes(),
        ),
        ("no vertices", "novertex.off", t("OFF\n0 0 0\n")),
        (
            "simplex of 100,000 vertices (message cut)",
            "wide.simplices",
            {
                let mut s = String::from("s");
                for i in 0..100_000 {
                    s.push_str(&format!(" {i}"));
                }
                s.into_bytes()
            },
        ),
        (
            "huge id implying a vertex count (no `v` lines)",
            "sparse.simplices",
            t("s 0 1\ns 0 1000000000 3 8 9\n"),
        ),
        (
            "binary junk",
            "junk.obj",
            vec![0xff, 0xfe, 0x00, 0x13, 0x80, 0x81, b'\n', 0xc3],
        ),
        ("unknown extension", "mesh.dxf", t("0\nSECTION\n")),
        ("missing file", "missing/nothing.off", Vec::new()),
        // Special files (made by `outcome`): refused before reading, never blocking.
        ("named pipe with no writer", "special/pipe.off", Vec::new()),
        (
            "device that never ends (`/dev/zero`, `/dev/urandom`)",
            "special/zero.obj",
            Vec::new(),
        ),
        ("directory", "special/dir.mesh", Vec::new()),
        // Echoed input: capped at 200 bytes and escaped.
        ("1 MB token", "long.simplices", {
            let mut v = b"s 0 ".to_vec();
            v.extend(std::iter::repeat_n(b'x', 1 << 20));
            v
        }),
        (
            "vertical tab inside a number",
            "vtab.off",
            t("OFF\n3 1 0\n0 0 0\n1\u{b}0 0 0\n0 1 0\n3 0 1 2\n"),
        ),
        ("NUL byte", "nul.obj", t("v 0 0 0\nv 1 0 0\nl 1 2\0\n")),
        (
            "no-break space between numbers",
            "nbsp.simplices",
            t("s 0 1\u{a0}2\n"),
        ),
        (
            "byte-order mark in the middle of the file",
            "bom-inside.mesh",
            t("MeshVersionFormatted 2\nDimension 3\n\u{feff}Vertices\n0\n"),
        ),
        (
            "binary header",
            "binary.simplices",
            b"\x00\x00\x00\x03\x00\x00\x00\x01s 0 1\n".to_vec(),
        ),
        // Line numbers.
        (
            "OFF header without its edge count (accepted)",
            "no-edge-count.off",
            t("OFF\n3 1\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
        ),
        (
            "OFF vertex colours without the `C` prefix",
            "colours.off",
            t("OFF\n3 1 0\n0 0 0 1 0 0 1\n1 0 0 0 1 0 1\n0 1 0 0 0 1 1\n3 0 1 2\n"),
        ),
        (
            "CR-only line ends (error on line 5)",
            "cr.off",
            t("OFF\r3 1 0\r0 0 0\r1 0 0\r0 1 x\r3 0 1 2\r"),
        ),
        (
            "CR-only line ends (accepted)",
            "cr.obj",
            t("v 0 0 0\rv 1 0 0\rv 0 1 0\rf 1 2 3\r"),
        ),
        // Numbers that would change silently.
        (
            "coordinate that overflows a double",
            "overflow.off",
            t("OFF\n2 1 0\n0 0 0\n1e309 0 0\n2 0 1\n"),
        ),
        (
            "coordinate that underflows to 0",
            "underflow.obj",
            t("v 0 0 0\nv 1e-400 0 0\nl 1 2\n"),
        ),
        (
            "OBJ free-form element",
            "curve.obj",
            t("v 0 0 0\nv 1 0 0\ncstype bspline\ndeg 1\ncurv 0 1 1 2\nend\n"),
        ),
        (
            "OBJ statement continued over 10^6 lines (accepted, linear time)",
            "continued.obj",
            {
                let mut s = String::from("v 0 0 0\nv 1 0 0\nl 1");
                for _ in 0..1_000_000 {
                    s.push_str(" 2 1 \\\n");
                }
                s.push('\n');
                s.into_bytes()
            },
        ),
        // Accepted inputs: the decisions the catalogue records.
        (
            "NaN / inf coordinates (accepted: topology ignores coordinates)",
            "nan.off",
            t("OFF\n3 1 0\nnan 0 0\ninf 0 0\n0 -inf 0\n3 0 1 2\n"),
        ),
        (
            "CRLF, tabs, no final newline (accepted)",
            "crlf.off",
            t("OFF\r\n3\t1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n3 0 1 2"),
        ),
        (
            "UTF-8 byte-order mark (accepted)",
            "bom.obj",
            t("\u{feff}v 0 0 0\nv 1 0 0\nl 1 2\n"),
        ),
        (
            "duplicate and face-of-another simplices (accepted, counted)",
            "dups.simplices",
            t("s 0 1 2\ns 2 0 1\ns 0 1\n"),
        ),
    ];
    cases.extend(new_format_cases());
    cases.extend(exact_reader_cases());
    cases.extend(data_cases());
    cases
}

/// Malformed data sections (issue 26): counts, types and values an attribute cannot hold, and
/// data no reader keeps yet, each refused naming the line and the array.
fn data_cases() -> Vec<(&'static str, &'static str, Vec<u8>)> {
    let t = |s: &str| s.as_bytes().to_vec();
    let tri = "POINTS 3 double\n0 0 0 1 0 0 0 1 0\nCELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n";
    let vtk = |body: &str| {
        format!("# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n{tri}{body}")
            .into_bytes()
    };
    let msh2 = |body: &str| format!("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n{body}").into_bytes();
    let medit = |body: &str| format!("MeshVersionFormatted 2\nDimension 3\n{body}").into_bytes();
    let nodes = "$Nodes\n2\n1 0 0 0\n2 1 0 0\n$EndNodes\n";
    let ply = |body: &str| format!("ply\nformat ascii 1.0\n{body}").into_bytes();
    // A PLY header up to the face element's vertex ids (3 vertices, 1 face).
    let ply_tri = "element vertex 3\nproperty float x\nproperty float y\nelement face 1\n\
                   property list uchar int vertex_indices\n";
    // A $NodeData section 't' (time step 0) of `comps` components declaring `count` rows.
    let node_data = |comps: usize, count: usize, rows: &[&str]| {
        format!(
            "$NodeData\n1\n\"t\"\n1\n0\n3\n0\n{comps}\n{count}\n{}\n$EndNodeData\n",
            rows.join("\n")
        )
    };
    vec![
        (
            "data count mismatch",
            "data-count.vtk",
            vtk("CELL_DATA 2\nSCALARS region int 1\nLOOKUP_TABLE default\n1 2\n"),
        ),
        (
            "data count mismatch",
            "field-count.vtk",
            vtk("POINT_DATA 3\nFIELD f 1\nt 1 2 double\n0 1\n"),
        ),
        (
            "data of the wrong type",
            "data-real.vtk",
            vtk("CELL_DATA 1\nSCALARS region int 1\nLOOKUP_TABLE default\n1.5\n"),
        ),
        (
            "data of the wrong type",
            "data-nan-label.vtk",
            vtk("CELL_DATA 1\nSCALARS region int 1\nLOOKUP_TABLE default\nnan\n"),
        ),
        (
            "partial data (refused: nothing holds \"no value\")",
            "face-colours.off",
            b"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 255 0 0\n2 0 1\n".to_vec(),
        ),
        (
            "data too wide",
            "normals.off",
            format!("NnOFF\n10\n1 0 0\n{}\n", ["0"; 20].join(" ")).into_bytes(),
        ),
        (
            "partial data (refused: nothing holds \"no value\")",
            "labels-partial.simplices",
            b"s 0 1 2 : 7\ns 1 2\n".to_vec(),
        ),
        (
            "data of the wrong type",
            "label-real.simplices",
            b"s 0 1 2 : 1.5\n".to_vec(),
        ),
        (
            "data of the wrong type",
            "smoothing.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\ns 1.5\nf 1 2 3\n".to_vec(),
        ),
        (
            "data not held (refused, never skipped)",
            "usemtl-nameless.obj",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl\nf 1 2 3\n".to_vec(),
        ),
        (
            "data of the wrong type",
            "ref-real.mesh",
            medit("Vertices\n1\n0 0 0 1.5\n"),
        ),
        (
            "data value overflows its type",
            "data-overflow.vtk",
            vtk("POINT_DATA 3\nSCALARS t float 1\nLOOKUP_TABLE default\n1 1e39 2\n"),
        ),
        (
            "data value overflows its type",
            "ref-range.mesh",
            medit("Vertices\n1\n0 0 0 4294967296\n"),
        ),
        (
            "data value overflows its type",
            "tag-range.msh",
            msh2(
                "$Nodes\n1\n1 0 0 0\n$EndNodes\n$Elements\n1\n1 15 2 3000000000 1 1\n$EndElements\n",
            ),
        ),
        (
            "data too wide",
            "data-components.vtk",
            vtk(
                "POINT_DATA 3\nFIELD f 1\nt 10 3 double\n0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n",
            ),
        ),
        (
            "data not held (refused, never skipped)",
            "data-lut.vtk",
            vtk("CELL_DATA 1\nLOOKUP_TABLE lut 1\n0 0 0 1\n"),
        ),
        (
            "data not held (refused, never skipped)",
            "elementnodedata.msh",
            msh2(&format!(
                "{nodes}$Elements\n1\n1 15 2 0 1 1\n$EndElements\n$ElementNodeData\n1\n\"t\"\n1\n0\n3\n0\n1\n1\n1 1 5\n$EndElementNodeData\n"
            )),
        ),
        (
            "data count mismatch",
            "nodedata-count.msh",
            msh2(&format!("{nodes}{}", node_data(1, 2, &["1 5"]))),
        ),
        (
            "partial data (refused: nothing holds \"no value\")",
            "nodedata-partial.msh",
            msh2(&format!("{nodes}{}", node_data(1, 1, &["2 5"]))),
        ),
        (
            "unknown node or element in data",
            "nodedata-node.msh",
            msh2(&format!("{nodes}{}", node_data(1, 2, &["1 5", "3 6"]))),
        ),
        (
            "data too wide",
            "nodedata-components.msh",
            msh2(&format!(
                "{nodes}{}",
                node_data(10, 2, &["1 0 0 0 0 0 0 0 0 0 0", "2 0 0 0 0 0 0 0 0 0 0"])
            )),
        ),
        (
            "data in the wrong place",
            "elementdata-before.msh",
            msh2(&format!(
                "{nodes}$ElementData\n1\n\"v\"\n0\n3\n0\n1\n1\n1 5\n$EndElementData\n"
            )),
        ),
        (
            "data not held (refused, never skipped)",
            "list-property.ply",
            ply(&format!(
                "{ply_tri}property list uchar float texcoord\nend_header\n0 0\n1 0\n0 1\n3 0 1 2 2 0 1\n"
            )),
        ),
        (
            "partial data (refused: nothing holds \"no value\")",
            "property-partial.ply",
            ply(&format!(
                "{ply_tri}property uchar red\nelement edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n0 0\n1 0\n0 1\n3 0 1 2 9\n0 1\n"
            )),
        ),
        (
            "data of the wrong type",
            "property-types.ply",
            ply(&format!(
                "{ply_tri}property uchar red\nelement edge 1\nproperty int vertex1\nproperty int vertex2\nproperty float red\nend_header\n0 0\n1 0\n0 1\n3 0 1 2 9\n0 1 0.5\n"
            )),
        ),
        (
            "data value overflows its type",
            "property-range.ply",
            ply(&format!(
                "{ply_tri}property uchar red\nend_header\n0 0\n1 0\n0 1\n3 0 1 2 256\n"
            )),
        ),
        (
            "data not held (refused, never skipped)",
            "names.msh",
            msh2("$PhysicalNames\n1\n2 1 unquoted\n$EndPhysicalNames\n"),
        ),
        (
            "data in the wrong place",
            "data-before.vtk",
            vtk("SCALARS region int 1\nLOOKUP_TABLE default\n1\n"),
        ),
        (
            "partial data (refused: nothing holds \"no value\")",
            "colour-partial.obj",
            t("v 0 0 0 1 0 0\nv 1 0 0\np 1 2\n"),
        ),
        (
            "data not held (refused, never skipped)",
            "vt-unreferenced.obj",
            t("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1 2 3\n"),
        ),
        (
            "unknown node or element in data",
            "vn-index.obj",
            t("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//2\n"),
        ),
        (
            "data not held (refused, never skipped)",
            "data-string.vtu",
            vtu(
                1,
                "<DataArray type=\"String\" Name=\"names\" format=\"ascii\">a b c</DataArray>\n",
                "",
            ),
        ),
        (
            "data not held (refused, never skipped)",
            "fielddata.vtu",
            vtu_with_field_data(),
        ),
        (
            "data not held (refused, never skipped)",
            "raw-appended.vtu",
            t(
                "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\">\n\
               <UnstructuredGrid>\n<Piece NumberOfPoints=\"1\" NumberOfCells=\"0\">\n<Points>\n\
               <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"appended\" \
               offset=\"0\"/>\n</Points>\n</Piece>\n</UnstructuredGrid>\n\
               <AppendedData encoding=\"raw\">\n_\u{18}\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\n\
               </AppendedData>\n</VTKFile>\n",
            ),
        ),
        (
            "data too wide",
            "data-components.vtu",
            vtu(
                1,
                "",
                "<DataArray type=\"Float64\" Name=\"w\" NumberOfComponents=\"10\" format=\"ascii\">0</DataArray>\n",
            ),
        ),
        (
            "data value overflows its type",
            "data-uint64.vtu",
            vtu(
                1,
                "<DataArray type=\"UInt64\" Name=\"id\" format=\"ascii\">1 2 9223372036854775808</DataArray>\n",
                "",
            ),
        ),
        (
            "data count mismatch",
            "data-count.vtu",
            vtu(
                1,
                "",
                "<DataArray type=\"Int32\" Name=\"region\" format=\"ascii\">1 2</DataArray>\n",
            ),
        ),
        (
            "data missing from a piece",
            "data-pieces.vtu",
            vtu(
                2,
                "<DataArray type=\"Int32\" Name=\"id\" format=\"ascii\">1 2 3</DataArray>\n",
                "",
            ),
        ),
    ]
}

/// A `.vtu` triangle with a `<FieldData>` array (a time value on the whole mesh).
fn vtu_with_field_data() -> Vec<u8> {
    let one = String::from_utf8(vtu(1, "", "")).unwrap();
    one.replace(
        "<UnstructuredGrid>\n",
        "<UnstructuredGrid>\n<FieldData>\n<DataArray type=\"Float64\" Name=\"TIME\" \
         NumberOfTuples=\"1\" format=\"ascii\">2.5</DataArray>\n</FieldData>\n",
    )
    .into_bytes()
}

/// A `.vtu` of `pieces` pieces, each a triangle; the first with `point` and `cell` data arrays.
fn vtu(pieces: usize, point: &str, cell: &str) -> Vec<u8> {
    let piece = |point: &str, cell: &str| {
        format!(
            "<Piece NumberOfPoints=\"3\" NumberOfCells=\"1\">\n<PointData>\n{point}</PointData>\n\
             <Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\
             0 0 0 1 0 0 0 1 0</DataArray>\n</Points>\n<Cells>\n\
             <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>\n\
             <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray>\n\
             <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">5</DataArray>\n\
             </Cells>\n<CellData>\n{cell}</CellData>\n</Piece>\n"
        )
    };
    let mut body = piece(point, cell);
    for _ in 1..pieces {
        body += &piece("", "");
    }
    format!(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\">\n\
         <UnstructuredGrid>\n{body}</UnstructuredGrid>\n</VTKFile>\n"
    )
    .into_bytes()
}

/// The readers of the formats issue 15 added (PLY, STL, legacy VTK, VTU, Gmsh MSH).
fn new_format_cases() -> Vec<(&'static str, &'static str, Vec<u8>)> {
    let t = |s: &str| s.as_bytes().to_vec();
    let ply = |body: &str| format!("ply\nformat ascii 1.0\n{body}").into_bytes();
    let vtk = |body: &str| {
        format!("# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n{body}")
            .into_bytes()
    };
    let msh2 = |body: &str| format!("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n{body}").into_bytes();
    let msh4 = |body: &str| format!("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n{body}").into_bytes();
    let nodes2 = "$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n";
    // A binary STL header declaring 10^9 triangles, with one.
    let mut stl_huge = vec![0u8; 80];
    stl_huge.extend_from_slice(&1_000_000_000u32.to_le_bytes());
    stl_huge.extend_from_slice(&[0u8; 50]);
    // One binary STL facet whose corners are all the same point.
    let mut stl_flat = vec![0u8; 80];
    stl_flat.extend_from_slice(&1u32.to_le_bytes());
    stl_flat.extend_from_slice(&[0u8; 50]);
    vec![
        ("empty file", "empty.ply", t("")),
        ("empty file", "empty.stl", t("")),
        ("empty file", "empty.vtk", t("")),
        ("empty file", "empty.vtu", t("")),
        ("empty file", "empty.msh", t("")),
        (
            "wrong header",
            "header.ply",
            t("PLY\nformat ascii 1.0\nend_header\n"),
        ),
        (
            "wrong header",
            "header.vtk",
            t("# vtk DataFile\nt\nASCII\n"),
        ),
        (
            "wrong header",
            "header.msh",
            t("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n"),
        ),
        (
            "wrong header",
            "header.vtu",
            t("<VTKFile type=\"PolyData\"></VTKFile>\n"),
        ),
        (
            "truncated file",
            "truncated.ply",
            ply("element vertex 2\nproperty float x\nproperty float y\nend_header\n0 0\n"),
        ),
        (
            "truncated file",
            "truncated.stl",
            t("solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"),
        ),
        (
            "truncated file",
            "truncated.vtk",
            vtk("POINTS 3 double\n0 0 0 1 0 0\n"),
        ),
        (
            "truncated file",
            "truncated.msh",
            msh2("$Nodes\n3\n1 0 0 0\n"),
        ),
        (
            "count far larger than the file",
            "huge.ply",
            ply("element vertex 4000000000\nproperty float x\nproperty float y\nend_header\n0 0\n"),
        ),
        ("count far larger than the file", "huge.stl", stl_huge),
        (
            "count far larger than the file",
            "huge.vtk",
            vtk("POINTS 4000000000 double\n0 0 0\n"),
        ),
        (
            "count far larger than the file",
            "huge.msh",
            msh4("$Nodes\n1 4000000000 1 4000000000\n"),
        ),
        (
            "polygon that is not a simplex",
            "quad.ply",
            ply(
                "element vertex 4\nproperty float x\nproperty float y\nelement face 1\n\
                 property list uchar int vertex_indices\nend_header\n0 0\n1 0\n1 1\n0 1\n4 0 1 2 3\n",
            ),
        ),
        (
            "polygon that is not a simplex",
            "quad.vtk",
            vtk(
                "POINTS 4 double\n0 0 0 1 0 0 1 1 0 0 1 0\nCELLS 1 5\n4 0 1 2 3\nCELL_TYPES 1\n9\n",
            ),
        ),
        (
            "polygon that is not a simplex",
            "quad.msh",
            msh2(&format!(
                "{nodes2}$Elements\n1\n1 3 2 0 1 1 2 3 3\n$EndElements\n"
            )),
        ),
        (
            "polygon that is not a simplex",
            "hex.vtu",
            t(
                "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\"><UnstructuredGrid>\
               <Piece NumberOfPoints=\"1\" NumberOfCells=\"1\"><Points>\
               <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0</DataArray>\
               </Points><Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0 0 0 0 0 0 0 0</DataArray>\
               <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">8</DataArray>\
               <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">12</DataArray>\
               </Cells></Piece></UnstructuredGrid></VTKFile>\n",
            ),
        ),
        (
            "negative id",
            "negative.vtk",
            vtk("POINTS 2 double\n0 0 0 1 0 0\nCELLS 1 3\n2 0 -1\nCELL_TYPES 1\n3\n"),
        ),
        (
            "out-of-range vertex id",
            "range.ply",
            ply(
                "element vertex 2\nproperty float x\nproperty float y\nelement edge 1\n\
                 property int vertex1\nproperty int vertex2\nend_header\n0 0\n1 0\n0 7\n",
            ),
        ),
        (
            "out-of-range vertex id",
            "range.msh",
            msh2(&format!(
                "{nodes2}$Elements\n1\n1 1 2 0 1 1 9\n$EndElements\n"
            )),
        ),
        ("repeated vertex in a simplex", "flat.stl", stl_flat),
        (
            "only DATASET UNSTRUCTURED_GRID",
            "polydata.vtk",
            t("# vtk DataFile Version 4.2\nt\nASCII\nDATASET POLYDATA\nPOINTS 0 float\n"),
        ),
        (
            "binary MSH in the other byte order",
            "big-endian.msh",
            b"$MeshFormat\n4.1 1 8\n\x00\x00\x00\x01\n$EndMeshFormat\n".to_vec(),
        ),
    ]
}

/// Issue 27 item 4: numbers exact in every reader (the declared float type included), no
/// element dropped silently, plain messages.
fn exact_reader_cases() -> Vec<(&'static str, &'static str, Vec<u8>)> {
    let t = |s: &str| s.as_bytes().to_vec();
    let ply = |y: &str, elements: &str, body: &str| {
        format!(
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
             property float z\n{elements}end_header\n0 0 0\n1 {y} 0\n0 1 0\n0 0 1\n{body}"
        )
        .into_bytes()
    };
    let face = "element face 1\nproperty list uchar int vertex_indices\n";
    let stl_facet = |x: &str| {
        format!(
            "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex {x} 0 0\nvertex 0 1 0\n\
             endloop\nendfacet\n"
        )
    };
    let vtk = |version: &str, ty: &str, x: &str, cells: &str| {
        format!(
            "# vtk DataFile Version {version}\nt\nASCII\nDATASET UNSTRUCTURED_GRID\n\
             POINTS 3 {ty}\n0 0 0 {x} 0 0 0 1 0\n{cells}"
        )
        .into_bytes()
    };
    let cells4 = "CELLS 1 4\n3 0 1 2\nCELL_TYPES 1\n5\n";
    let msh2 = |nodes: &str, elements: &str| {
        format!(
            "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n{nodes}$EndNodes\n\
             $Elements\n1\n{elements}$EndElements\n"
        )
        .into_bytes()
    };
    let nodes = "1 0 0 0\n2 1 0 0\n3 0 1 0\n";
    let triangle = "1 2 2 0 1 1 2 3\n";
    // A binary STL declaring 2 triangles with 1.
    let mut stl_cut = vec![0u8; 80];
    stl_cut.extend_from_slice(&2u32.to_le_bytes());
    stl_cut.extend_from_slice(&[0u8; 50]);
    vec![
        (
            "number a declared 32-bit float cannot hold",
            "float-overflow.ply",
            ply("1e39", face, "3 0 1 2\n"),
        ),
        (
            "number a declared 32-bit float cannot hold",
            "float-underflow.ply",
            ply("1e-400", face, "3 0 1 2\n"),
        ),
        (
            "number a declared 32-bit float cannot hold",
            "float-underflow.stl",
            format!("solid a\n{}endsolid a\n", stl_facet("1e-50")).into_bytes(),
        ),
        (
            "number a declared 32-bit float cannot hold",
            "float-overflow.vtk",
            vtk("4.2", "float", "1e39", cells4),
        ),
        (
            "number a declared 32-bit float cannot hold",
            "float-overflow.vtu",
            t(
                "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\"><UnstructuredGrid>\
               <Piece NumberOfPoints=\"1\" NumberOfCells=\"1\"><Points>\
               <DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">0 1e39 0</DataArray>\
               </Points><Cells><DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">0</DataArray>\
               <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">1</DataArray>\
               <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">1</DataArray>\
               </Cells></Piece></UnstructuredGrid></VTKFile>\n",
            ),
        ),
        (
            "coordinate that overflows a double",
            "overflow.vtk",
            vtk("4.2", "double", "1e309", cells4),
        ),
        (
            "coordinate that underflows to 0",
            "underflow.vtk",
            vtk("4.2", "double", "1e-400", cells4),
        ),
        (
            "coordinate that overflows a double",
            "overflow.msh",
            msh2("1 0 0 0\n2 1e309 0 0\n3 0 1 0\n", triangle),
        ),
        (
            "coordinate that underflows to 0",
            "underflow.msh",
            msh2("1 0 0 0\n2 1e-400 0 0\n3 0 1 0\n", triangle),
        ),
        (
            "NaN / inf coordinates in ASCII PLY (accepted, as in every reader)",
            "nan.ply",
            ply("nan", face, "3 0 1 2\n"),
        ),
        (
            "extra value on an element line",
            "extra-value.ply",
            ply("0", face, "3 0 1 2 3\n"),
        ),
        (
            "extra value on an element line",
            "extra-value.msh",
            msh2(nodes, "1 2 2 0 1 1 2 3 3\n"),
        ),
        (
            "PLY tetra elements (accepted: tetrahedra)",
            "tetra.ply",
            ply(
                "0",
                "element tetra 1\nproperty list uchar int vertex_indices\n",
                "4 0 1 2 3\n",
            ),
        ),
        (
            "PLY tristrips (accepted: each strip's triangles)",
            "tristrips.ply",
            ply(
                "0",
                "element tristrips 1\nproperty list int int vertex_indices\n",
                "4 0 1 2 3\n",
            ),
        ),
        (
            "PLY element with vertex ids that is not read",
            "polyline.ply",
            ply(
                "0",
                "element polyline 1\nproperty list uchar int vertex_indices\n",
                "4 0 1 2 3\n",
            ),
        ),
        (
            "several ASCII STL solids (accepted: all read)",
            "two-solids.stl",
            format!(
                "solid a\n{}endsolid a\nsolid b\n{}endsolid b\n",
                stl_facet("1"),
                stl_facet("2")
            )
            .into_bytes(),
        ),
        ("truncated binary STL", "cut.stl", stl_cut),
        (
            "one-line OFF (accepted)",
            "one-line.off",
            t("OFF 3 1 0 0 0 0 1 0 0 0 1 0 3 0 1 2"),
        ),
        (
            "unsupported legacy VTK version",
            "version.vtk",
            vtk("9.9", "double", "1", cells4),
        ),
        (
            "VTK 5.1 offsets not covering the connectivity",
            "offsets.vtk",
            vtk(
                "5.1",
                "double",
                "1",
                "CELLS 2 5\nOFFSETS vtktypeint64\n1 4\nCONNECTIVITY vtktypeint64\n9 0 1 2 9\n\
                 CELL_TYPES 1\n5\n",
            ),
        ),
        (
            "section shorter than declared",
            "short-node.msh",
            msh2("1 0 0 0\n2 1 0 0\n3 0 1\n", triangle),
        ),
        (
            "element type that is not a simplex type",
            "type99.msh",
            msh2(nodes, "1 99 2 0 1 1 2 3\n"),
        ),
        (
            "element count disagreeing with the blocks",
            "count.msh",
            t(
                "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 3 1 3\n2 1 0 3\n1\n2\n3\n\
               0 0 0\n1 0 0\n0 1 0\n$EndNodes\n$Elements\n1 2 1 1\n2 1 2 1\n1 1 2 3\n\
               $EndElements\n",
            ),
        ),
    ]
}

fn outcome(dir: &std::path::Path, name: &str, content: &[u8]) -> String {
    let path = dir.join(name);
    if let Some(special) = name.strip_prefix("special/") {
        std::fs::create_dir_all(dir.join("special")).unwrap();
        make_special(&path, special);
    } else if !name.starts_with("missing/") {
        std::fs::write(&path, content).unwrap();
    }
    match Complex::from_path(&path) {
        Ok(c) => {
            let s = c.stats();
            format!(
                "accepted: dimension {}, {} vertices, {} absorbed",
                c.dimension(),
                c.vertex_count(),
                s.absorbed_duplicates + s.absorbed_faces
            )
        }
        // Paths are temporary: show the file name only.
        Err(e) => e.to_string().replace(&format!("{}/", dir.display()), ""),
    }
}

/// A named pipe (no writer ever opens it), a link to `/dev/zero`, or a directory.
fn make_special(path: &std::path::Path, name: &str) {
    match name {
        "pipe.off" => {
            let ok = std::process::Command::new("mkfifo")
                .arg(path)
                .status()
                .is_ok_and(|s| s.success());
            assert!(ok, "mkfifo failed");
        }
        "zero.obj" => std::os::unix::fs::symlink("/dev/zero", path).unwrap(),
        "dir.mesh" => std::fs::create_dir_all(path).unwrap(),
        _ => unreachable!("{name}"),
    }
}

#[test]
fn every_bad_input_gets_the_catalogued_error() {
    let dir: PathBuf = std::env::temp_dir().join(format!("topoplex-bad-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut rows = String::new();
    for (class, name, content) in cases() {
        let got = outcome(&dir, name, &content);
        // Every refusal names the file; every line-specific one also the line.
        if !got.starts_with("accepted") {
            assert!(
                got.contains(name.rsplit('/').next().unwrap()),
                "{name}: {got}"
            );
        }
        rows.push_str(&format!(
            "| {class} | `{name}` | {} |\n",
            got.replace('|', "\\|")
        ));
    }
    std::fs::remove_dir_all(&dir).ok();
    let table = format!("| class | file | what `Complex::from_path` says |\n|---|---|---|\n{rows}");
    common::check_bad_input_doc("readers", &table, "it bad_input::");
}

/// (class, file name, content) read with `--triangulate` (`ReadOptions::triangulate`): polygons
/// that are fanned, and one of each reason a polygon is refused, in each format that keeps them.
fn triangulate_cases() -> Vec<(&'static str, &'static str, Vec<u8>)> {
    let t = |s: &str| s.as_bytes().to_vec();
    let off = |faces: &str| {
        t(&format!(
            "OFF\n5 1 0\n0 0 0\n2 0 0\n2 1 0\n1 2 0\n0 1 0\n{faces}\n"
        ))
    };
    let ply = |points: &str, face: &str| {
        t(&format!(
            "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
             property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
             property int region\nend_header\n{points}{face}\n"
        ))
    };
    let vtk = |points: &str, cells: &str, types: &str| {
        t(&format!(
            "# vtk DataFile Version 4.2\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 4 double\n\
             {points}\nCELLS 1 {}\n{cells}\nCELL_TYPES 1\n{types}\n",
            cells.split_whitespace().count()
        ))
    };
    let square = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
    vec![
        (
            "convex pentagon (fanned)",
            "pentagon.off",
            off("5 0 1 2 3 4"),
        ),
        (
            "convex quad (fanned)",
            "quad.obj",
            t("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"),
        ),
        (
            "convex quad (fanned)",
            "quad.ply",
            ply(square, "4 0 1 2 3 5"),
        ),
        (
            "quad cell (fanned)",
            "quad.vtk",
            vtk(square, "4 0 1 2 3", "9"),
        ),
        (
            "polygon cell (fanned)",
            "polygon.vtk",
            vtk(square, "4 0 1 2 3", "7"),
        ),
        (
            "non-planar polygon",
            "bent.obj",
            t("v 0 0 0\nv 1 0 0\nv 1 1 0.01\nv 0 1 0\nf 1 2 3 4\n"),
        ),
        (
            "non-planar polygon",
            "bent.ply",
            ply("0 0 0\n1 0 0\n1 1 0.5\n0 1 0\n", "4 0 1 2 3 5"),
        ),
        (
            "non-planar polygon",
            "bent.vtk",
            vtk("0 0 0 1 0 0 1 1 1 0 1 0", "4 0 1 2 3", "9"),
        ),
        ("non-convex polygon", "arrow.off", off("4 0 1 3 2")),
        (
            "non-convex polygon",
            "arrow.ply",
            ply("0 0 0\n1 0 0\n0.2 0.2 0\n0 1 0\n", "4 0 1 2 3 5"),
        ),
        (
            "star polygon (winds twice)",
            "star.obj",
            t(
                "v 1 0 0\nv 0.309 0.951 0\nv -0.809 0.588 0\nv -0.809 -0.588 0\nv 0.309 -0.951 0\n\
             f 1 3 5 2 4\n",
            ),
        ),
        ("repeated vertex", "repeat.off", off("4 0 1 2 1")),
        (
            "repeated vertex",
            "repeat.vtk",
            vtk(square, "4 0 1 2 1", "7"),
        ),
        (
            "collinear vertices (zero-area triangle)",
            "collinear.off",
            t("OFF\n4 1 0\n0 0 0\n1 0 0\n2 0 0\n1 1 0\n4 0 1 2 3\n"),
        ),
        (
            "coincident vertices",
            "coincident.obj",
            t("v 0 0 0\nv 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 4\n"),
        ),
        (
            "zero area",
            "flat.off",
            t("OFF\n4 1 0\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n4 0 1 2 3\n"),
        ),
        ("vertex without coordinates", "beyond.off", off("4 0 1 2 9")),
        (
            "coordinates of 4 components",
            "four.off",
            t("4OFF\n4 1 0\n0 0 0 0\n1 0 0 0\n1 1 0 0\n0 1 0 0\n4 0 1 2 3\n"),
        ),
        (
            "quadrangle (fanned, tags kept)",
            "quad.msh",
            t(
                "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n\
               4 0 1 0\n$EndNodes\n$Elements\n1\n1 3 2 7 1 1 2 3 4\n$EndElements\n",
            ),
        ),
        (
            "non-convex quadrangle",
            "arrow.msh",
            t(
                "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 0\n\
               3 0.2 0.2 0\n4 0 1 0\n$EndNodes\n$Elements\n1\n1 3 2 7 1 1 2 3 4\n\
               $EndElements\n",
            ),
        ),
        (
            "per-corner data on a polygon",
            "flat-quad.obj",
            t("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 -1\n\
               f 1//1 2//1 3//1 4//1\nf 1//2 4//2 3//2\n"),
        ),
        (
            "polygon in a format not fanned (refused as without the flag)",
            "quad.mesh",
            t(
                "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 1\n1 0 0 1\n1 1 0 1\n\
               0 1 0 1\nQuadrilaterals\n1\n1 2 3 4 0\n",
            ),
        ),
    ]
}

#[test]
fn every_polygon_read_with_triangulate_is_fanned_or_refused_with_the_reason() {
    use topoplex::io::ReadOptions;
    let dir: PathBuf =
        std::env::temp_dir().join(format!("topoplex-bad-tri-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let options = ReadOptions { triangulate: true };
    let mut rows = String::new();
    for (class, name, content) in triangulate_cases() {
        let path = dir.join(name);
        std::fs::write(&path, &content).unwrap();
        let got = match Complex::from_path_options(&path, Default::default(), options) {
            Ok(c) => {
                // Fanned: only triangles, as many as the polygon's vertices less 2, every
                // polygon refused without the flag.
                assert!(
                    Complex::from_path(&path).is_err(),
                    "{name} read without the flag"
                );
                let attributes: Vec<String> = c.attributes().iter().map(|a| a.describe()).collect();
                format!(
                    "accepted: {} triangles{}",
                    c.top_counts()[2],
                    if attributes.is_empty() {
                        String::new()
                    } else {
                        format!(", {}", attributes.join(", "))
                    }
                )
            }
            Err(e) => {
                let msg = e.to_string().replace(&format!("{}/", dir.display()), "");
                assert!(msg.contains(name), "{name}: {msg}");
                msg
            }
        };
        rows.push_str(&format!(
            "| {class} | `{name}` | {} |\n",
            got.replace('|', "\\|")
        ));
    }
    std::fs::remove_dir_all(&dir).ok();
    let table = format!(
        "| class | file | what `Complex::from_path_options` (`--triangulate`) says |\n\
         |---|---|---|\n{rows}"
    );
    common::check_bad_input_doc("triangulate", &table, "bad_input");
}
