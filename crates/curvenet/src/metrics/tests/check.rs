use super::*;

#[test]
fn the_reader_property_holds_on_good_bad_and_binary_input() {
    use crate::io::NetworkFormat;
    let good = crate::io::network_to_string(
        &crate::network::examples::example("sphere").expect("bundled sphere"),
        NetworkFormat::Json,
    );
    assert_eq!(check_network_reader(good.as_bytes(), NetworkFormat::Json), Ok(()));
    for bytes in [&b"{\"curves\": [{\"points\": [[0,0,"[..], b"\xff\xfe", b"", b"v 1 2\nl 1 2\n"] {
        for format in [NetworkFormat::Json, NetworkFormat::Obj, NetworkFormat::Net] {
            assert_eq!(check_network_reader(bytes, format), Ok(()));
        }
    }
}
