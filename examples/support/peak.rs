//! The process's peak resident memory (Linux: /proc/self/status VmHWM), in bytes; 0 where it
//! cannot be read. Shared by the measuring examples (`#[path]`-included).

/// VmHWM in bytes.
pub fn peak_bytes() -> u64 {
    let s = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let kib = s
        .lines()
        .find(|l| l.starts_with("VmHWM:"))
        .and_then(|l| l.split_whitespace().nth(1))
        .and_then(|n| n.parse::<u64>().ok())
        .unwrap_or(0);
    kib * 1024
}
