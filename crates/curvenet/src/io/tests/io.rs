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

#[test]
fn obj_and_net_refuse_networks_they_cannot_hold() {
    let mut net = crate::network::examples::example("sphere").unwrap();
    net.curves[1].normals.clear();
    let dir = std::env::temp_dir().join(format!("curvenet-io-mixed-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["m.obj", "m.net"] {
        let e = write_network(&dir.join(name), &net).unwrap_err();
        assert!(matches!(e, crate::Error::Usage { .. }), "{e}");
        assert!(!dir.join(name).exists());
    }
    assert_eq!(network_to_string(&net, NetworkFormat::Net), "");
    write_network(&dir.join("m.json"), &net).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_byte_order_mark_is_skipped_and_control_characters_in_names_are_escaped() {
    let text = "\u{feff}{\"curves\": [{\"name\": \"a\\u001b[31mred\", \"points\": [[0,0,0],[1,0,0]]}]}";
    let net = parse_network(text, NetworkFormat::Json, "bom.json").unwrap();
    let label = crate::network::curve_label(&net.curves, 0);
    assert!(!label.chars().any(char::is_control), "{label}");
    assert!(label.contains("\\u{1b}[31mred"), "{label}");
    assert!(parse_network("\u{feff}v 0 0 0\nv 1 0 0\nl 1 2\n", NetworkFormat::Obj, "bom.obj").is_ok());
}
