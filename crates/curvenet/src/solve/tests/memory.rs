use super::*;

#[test]
fn cache_sizes_are_read_as_sysfs_writes_them() {
    assert_eq!(parse_size("48K"), Some(48.0 * 1024.0));
    assert_eq!(parse_size("480M"), Some(480.0 * 1024.0 * 1024.0));
    assert_eq!(parse_size("1G"), Some(1024.0 * 1024.0 * 1024.0));
    assert_eq!(parse_size("512"), Some(512.0));
    assert_eq!(parse_size("12 K"), None);
    assert_eq!(parse_size("K"), None);
}

/// The workspace is at least private-gemm-x86's floor (2 × 2 MiB), a whole number of pages,
/// and at least twice the largest cache the machine reports.
#[test]
fn the_matrix_products_workspace_covers_twice_the_largest_cache() {
    let w = gemm_workspace_bytes();
    assert!(w >= 4.0 * 1024.0 * 1024.0, "{w}");
    assert_eq!(w % 4096.0, 0.0);
    let largest = cache_bytes_by_level().into_iter().fold(0.0, f64::max);
    assert!(w >= 2.0 * largest, "{w} < 2 × {largest}");
}

/// Under a limit, the threads that may run products leave half of what the limit leaves
/// beyond the reserve to the data, but one always runs.
#[test]
fn threads_fit_the_address_space_left() {
    let w = gemm_workspace_bytes();
    assert_eq!(threads_within(RESERVED_BYTES), 1);
    assert_eq!(threads_within(0.0), 1);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    assert_eq!(threads_within(RESERVED_BYTES + 2.0 * w * cores as f64 + 1.0), cores);
    if cores >= 2 {
        assert_eq!(threads_within(RESERVED_BYTES + 2.0 * w * 1.5), 1);
    }
}
