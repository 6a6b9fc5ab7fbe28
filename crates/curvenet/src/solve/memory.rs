//! The memory a process may use: its address-space limit and the machine's available memory
//! (Linux: `/proc/self/limits`, `/proc/meminfo`), for the estimates that refuse runs too large
//! for it (the pipeline's budget, the ghost bases of `cauchy` and `fit`, `inflate`)
//! before an allocation aborts.

/// Address space a process reserves beyond what it uses (thread stacks, allocator arenas,
/// freed pages not yet returned): left out of an address-space limit. Under `ulimit -v 4000000`
/// a default run of 4.5·10⁵ vertices passes (peak resident 2.0 GB) and one of 6.8·10⁵ fails
/// at 1.9 GB resident, allocating 1.1 GB more.
const RESERVED_BYTES: f64 = 1.3e9;

/// The memory a run may take: `max` when given, else the smaller of the process's
/// address-space limit (less the address space reserved beyond use, 1.3 GB) and the machine's
/// available memory; `None` when neither is known (not Linux).
pub fn available_memory(max: Option<f64>) -> Option<f64> {
    if let Some(m) = max {
        return Some(m);
    }
    let limit = address_space_limit().map(|l| l - RESERVED_BYTES);
    match (limit, machine_available()) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// The soft address-space limit of this process (`ulimit -v`), in bytes; `None` when unlimited
/// or unknown.
fn address_space_limit() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = text.lines().find(|l| l.starts_with("Max address space"))?;
    let soft = line.trim_start_matches("Max address space").split_whitespace().next()?;
    soft.parse::<f64>().ok()
}

/// The machine's available memory (`MemAvailable` of /proc/meminfo), in bytes.
fn machine_available() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb = line.split_whitespace().nth(1)?.parse::<f64>().ok()?;
    Some(kb * 1024.0)
}
