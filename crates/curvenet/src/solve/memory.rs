//! The memory a process may use: its address-space limit and the machine's available memory
//! (Linux: `/proc/self/limits`, `/proc/meminfo`), for the estimates that refuse runs too large
//! for it (the pipeline's budget, the ghost bases of `cauchy` and `fit`, `inflate`)
//! before an allocation aborts.

/// Address space a process reserves beyond what it uses (thread stacks, allocator arenas,
/// freed pages not yet returned): left out of an address-space limit. Under `ulimit -v 4000000`
/// a default run of 4.5·10⁵ vertices passes (peak resident 2.0 GB) and one of 6.8·10⁵ fails
/// at 1.9 GB resident, allocating 1.1 GB more (measured on a machine with small caches; the
/// matrix products' workspaces, [`gemm_workspace_bytes`], are left out besides).
const RESERVED_BYTES: f64 = 1.3e9;

/// The memory a run may take: `max` when given, else the smaller of the process's
/// address-space limit (less the matrix products' workspaces of the threads that may run them,
/// [`gemm_workspace_bytes`], and half the address space reserved beyond use, 0.65 GB) and the
/// machine's available memory; `None` when neither is known (not Linux). At least zero.
pub fn available_memory(max: Option<f64>) -> Option<f64> {
    if let Some(m) = max {
        return Some(m);
    }
    let limit = address_space_limit().map(|l| {
        let threads = threads_within(l) + 1;
        // Half the reserve beside the workspaces: with two 0.96 GB workspaces a run of 1.1·10⁵
        // vertices passes under `ulimit -v 3000000` and one of 2·10⁵ aborts (budget 0.35 GB:
        // ~7.5·10⁴); under 4000000, 4.2·10⁵ pass (budget 1.35 GB: ~2.9·10⁵).
        (l - 0.5 * RESERVED_BYTES - threads as f64 * gemm_workspace_bytes()).max(0.0)
    });
    match (limit, machine_available()) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// The memory reading an input may take: as [`available_memory`] without the matrix products'
/// workspaces (reading multiplies no matrices; a command that goes on to solve is refused by
/// its own budget, naming the solve).
pub fn available_for_reading() -> Option<f64> {
    let limit = address_space_limit().map(|l| (l - RESERVED_BYTES).max(0.0));
    match (limit, machine_available()) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// Under an address-space limit (`ulimit -v`), sizes the global thread pool so that the matrix
/// products' workspaces fit beside the data ([`threads_within`]) and returns the number of
/// worker threads chosen; `None` (nothing done) without a limit, when `RAYON_NUM_THREADS` is
/// set, or when the pool was already built. Front ends call it first thing: faer's products
/// reserve a thread-local workspace of twice the L3 cache they detect in every thread that runs
/// one (0.96 GB each on a machine reporting a 480 MB L3), and three such threads under
/// `ulimit -v 4000000` abort the process on an allocation failure.
pub fn fit_thread_pool_to_address_space() -> Option<usize> {
    let limit = address_space_limit()?;
    if std::env::var_os("RAYON_NUM_THREADS").is_some() {
        return None;
    }
    let threads = threads_within(limit);
    rayon::ThreadPoolBuilder::new().num_threads(threads).build_global().ok()?;
    Some(threads)
}

/// Worker threads that may run matrix products under the address-space limit `limit`: as many
/// workspaces ([`gemm_workspace_bytes`]) as fill half of what the limit leaves beyond the
/// reserved 1.3 GB, at least one, at most the machine's cores.
pub fn threads_within(limit: f64) -> usize {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let fit = ((limit - RESERVED_BYTES).max(0.0) / (2.0 * gemm_workspace_bytes())).floor() as usize;
    fit.clamp(1, cores)
}

/// The address space faer's dense matrix products reserve in each thread that runs one:
/// private-gemm-x86 (0.1) keeps a thread-local packing workspace of twice the L3 cache it
/// detects, the L3 taken at least 2 MiB and at least four L2 (the L2 at least 256 KiB and four
/// L1). The same rule on the cache sizes of the first core
/// (`/sys/devices/system/cpu/cpu0/cache/index*/`, levels 1–3); 4 MiB when they are unknown.
/// (Measured: 0.96 GB per thread on a machine reporting a 480 MB L3, where three such threads
/// under `ulimit -v 4000000` aborted a small run.)
pub fn gemm_workspace_bytes() -> f64 {
    let caches = cache_bytes_by_level();
    let level = |l: usize| caches.get(l).copied().unwrap_or(0.0);
    let l1 = level(1).max(32.0 * 1024.0);
    let l2 = level(2).max(256.0 * 1024.0).max(4.0 * l1);
    let l3 = level(3).max(2.0 * 1024.0 * 1024.0).max(4.0 * l2);
    2.0 * (l3 / 4096.0).ceil() * 4096.0
}

/// The largest data or unified cache of the first core at each level 1–3 (index = level),
/// in bytes; zero where unknown.
fn cache_bytes_by_level() -> [f64; 4] {
    let mut sizes = [0.0; 4];
    let Ok(dirs) = std::fs::read_dir("/sys/devices/system/cpu/cpu0/cache") else {
        return sizes;
    };
    for dir in dirs.flatten() {
        let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).ok();
        if read("type").is_some_and(|t| t.trim() == "Instruction") {
            continue;
        }
        let level = read("level").and_then(|l| l.trim().parse::<usize>().ok()).filter(|&l| (1..=3).contains(&l));
        let (Some(level), Some(size)) = (level, read("size").and_then(|s| parse_size(s.trim()))) else {
            continue;
        };
        sizes[level] = sizes[level].max(size);
    }
    sizes
}

/// A cache size as sysfs writes it (`48K`, `2048K`, `480M`), in bytes.
fn parse_size(text: &str) -> Option<f64> {
    let split = text.find(|c: char| !c.is_ascii_digit()).unwrap_or(text.len());
    let (digits, unit) = text.split_at(split);
    let scale = match unit {
        "" => 1.0,
        "K" => 1024.0,
        "M" => 1024.0 * 1024.0,
        "G" => 1024.0 * 1024.0 * 1024.0,
        _ => return None,
    };
    Some(digits.parse::<f64>().ok()? * scale)
}

/// The soft address-space limit of this process (`ulimit -v`), in bytes; `None` when unlimited
/// or unknown.
pub fn address_space_limit() -> Option<f64> {
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

#[cfg(test)]
#[path = "tests/memory.rs"]
mod tests;
