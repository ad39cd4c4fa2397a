use super::read_off_in_pieces;
use crate::complex::{RawInput, xorshift_below};
use crate::io::off;
use crate::io::tests::TempFile;

/// An OFF text drawn at random, and whether it was drawn in the form the stream takes (one
/// entry a line, `OFF` header, triangles and edges of distinct ids in range, no colour): most
/// are; the rest carry one of the things that send a file to the general read.
fn draw(below: &mut impl FnMut(u64) -> u64) -> (String, bool) {
    let mut plain = true;
    let end = ["\n", "\r\n", "\r"][below(3) as usize];
    let mut out = String::new();
    let line = |out: &mut String, text: &str, below: &mut dyn FnMut(u64) -> u64| {
        match below(12) {
            0 => out.push_str(&format!("# a comment 1 2 3{end}")),
            1 => out.push_str(&format!("  \t{end}")),
            _ => {}
        }
        out.push_str(text);
        if below(10) == 0 {
            out.push_str(" # trailing 4 5");
        }
        out.push_str(end);
    };
    let nv = 1 + below(12) as u32;
    let nf = below(15) as u32;
    let header = match below(25) {
        0 => {
            plain = false;
            "COFF"
        }
        _ => "OFF",
    };
    if below(6) == 0 {
        line(&mut out, &format!("{header} {nv} {nf} 0"), below);
    } else {
        line(&mut out, header, below);
        line(&mut out, &format!("{nv} {nf} {}", below(9)), below);
    }
    let numbers = [
        "0", "1.5", "-2e3", "7", "0.125", "nan", "-inf", "1e400", "1e-400", "x",
    ];
    let mut pending = String::new();
    for i in 0..nv {
        let xyz: Vec<&str> = (0..3)
            .map(|_| {
                let range = if below(60) == 0 { 10 } else { 5 };
                numbers[below(range) as usize]
            })
            .collect();
        let text = xyz.join(" ");
        match below(300) {
            // Split over two lines, or two vertices on one line.
            0 => {
                plain = false;
                line(&mut out, &xyz[..1].join(" "), below);
                line(&mut out, &xyz[1..].join(" "), below);
            }
            1 if i + 1 < nv => {
                plain = false;
                pending = text;
            }
            _ if !pending.is_empty() => {
                line(&mut out, &format!("{pending} {text}"), below);
                pending.clear();
            }
            _ => line(&mut out, &text, below),
        }
    }
    let faces = nf - u32::from(below(25) == 0 && nf > 0);
    for _ in 0..faces {
        let k = match below(60) {
            0 => 1,
            1 => 4,
            2..=9 => 2,
            _ => 3,
        };
        if k == 1 || k == 4 || k > nv as usize {
            plain = false;
        }
        let mut ids: Vec<u32> = Vec::new();
        while ids.len() < k {
            let v = match below(300) {
                0 => {
                    plain = false;
                    nv + below(3) as u32
                }
                1 if !ids.is_empty() => {
                    plain = false;
                    ids[0]
                }
                _ => below(nv as u64) as u32,
            };
            if !ids.contains(&v) || below(300) == 0 {
                if ids.contains(&v) {
                    plain = false;
                }
                ids.push(v);
            }
        }
        let mut text = format!("{k}");
        for v in &ids {
            text.push_str(&format!(" {v}"));
        }
        if below(300) == 0 {
            plain = false;
            text.push_str(" 0.5 0.5 0.5");
        }
        line(&mut out, &text, below);
    }
    if below(25) == 0 {
        out.push_str("junk");
    }
    if below(4) == 0 {
        out.truncate(out.trim_end_matches(['\r', '\n']).len());
    }
    (out, plain)
}

/// The tables a general read's listing makes: each simplex in its dimension's table, in order,
/// and the vertices' use counts.
fn tables_of(raw: &RawInput) -> (Vec<Vec<u32>>, Vec<u32>) {
    let mut tops = vec![Vec::new(); crate::complex::MAX_DIMENSION + 1];
    let mut uses = vec![0u32; raw.vertex_count.unwrap() as usize];
    for i in 0..raw.simplex_count() {
        let s = raw.simplex(i);
        tops[s.len() - 1].extend_from_slice(s);
        for &v in s {
            uses[v as usize] += 1;
        }
    }
    (tops, uses)
}

/// 3,000 random OFF texts, each streamed through buffers of 1, 2, 5, 16 bytes and 1 MiB (entries
/// and line ends across pieces, lines longer than the buffer): whenever the stream answers, the
/// general reader reads the same file without error and its listing is the stream's tables,
/// coordinates bit for bit; and every file drawn in the plain form that the general reader
/// reads is answered by the stream.
#[test]
fn streamed_off_tables_equal_the_general_readers_listing() {
    let mut below = xorshift_below(0x5eed_0ff5);
    let (mut answered, mut general) = (0, 0);
    for case in 0..3000 {
        let (text, plain) = draw(&mut below);
        let f = TempFile::new(&format!("plain-{case}.off"), text.as_bytes());
        let want = off::parse(&text);
        for piece in [1, 2, 5, 16, 1 << 20] {
            let got = read_off_in_pieces(&f.0, piece);
            match (&got, &want) {
                (Some(t), Ok(raw)) => {
                    assert_eq!(Some(t.vertex_count), raw.vertex_count, "{text:?}");
                    assert!(raw.attributes.is_empty(), "{text:?}");
                    let c = raw.coords.as_ref().unwrap();
                    assert_eq!(t.coords.dim, c.dim);
                    let bits = |d: &[f64]| d.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
                    assert_eq!(bits(&t.coords.data), bits(&c.data), "{text:?}");
                    let (tops, uses) = tables_of(raw);
                    assert_eq!(t.tops, tops, "{text:?}");
                    assert_eq!(t.uses, uses, "{text:?}");
                }
                (Some(_), Err(e)) => panic!("streamed a file the reader refuses ({e:?}): {text:?}"),
                (None, Ok(_)) => assert!(!plain, "a plain file was not streamed: {text:?}"),
                (None, Err(_)) => {}
            }
            answered += usize::from(got.is_some());
        }
        general += usize::from(want.is_ok() && plain);
    }
    assert!(general > 300, "only {general} plain files read");
    assert!(answered >= 5 * general, "{answered} streamed of {general}");
}

/// What the stream leaves to the general read, each on its own: a count the file cannot hold
/// (nothing reserved for it), a one-line OFF, a colour, a polygon, a file that is not UTF-8.
#[test]
fn files_the_stream_leaves_to_the_general_read() {
    let cases: [&[u8]; 6] = [
        b"OFF\n4000000000 1 0\n0 0 0\n",
        b"OFF 3 1 0 0 0 0 1 0 0 0 1 0 3 0 1 2\n",
        b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 0 0\n",
        b"OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n4 0 1 2 3\n",
        b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 # \xff\n",
        b"OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    ];
    for (i, bytes) in cases.iter().enumerate() {
        let f = TempFile::new(&format!("left-{i}.off"), bytes);
        assert!(read_off_in_pieces(&f.0, 1 << 20).is_none(), "case {i}");
    }
    let f = TempFile::new("taken.off", b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    let t = read_off_in_pieces(&f.0, 1 << 20).expect("a plain triangle is streamed");
    assert_eq!(t.tops[2], [0, 1, 2]);
    assert_eq!(t.uses, [1, 1, 1]);
}
