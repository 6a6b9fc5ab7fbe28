use super::*;

#[test]
fn tokens_have_columns() {
    let mut t = Tokens::of_line(3, "v  1.0 x # comment");
    assert_eq!(t.next(), Some((1, "v")));
    assert_eq!(t.next(), Some((4, "1.0")));
    assert_eq!(t.next(), Some((8, "x")));
    assert_eq!(t.next(), None);
}

#[test]
fn atomic_write_leaves_nothing_on_failure() {
    let dir = std::env::temp_dir().join(format!("curvenet-atomic-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("out.txt");
    std::fs::write(&path, "old").unwrap();
    let r = write_atomic(&path, |w| {
        w.write_all(b"partial")?;
        Err(std::io::Error::other("boom"))
    });
    assert!(r.is_err());
    assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}
