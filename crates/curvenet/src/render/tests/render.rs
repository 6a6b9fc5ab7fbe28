use super::*;

#[test]
fn values_are_formatted_with_three_digits() {
    assert_eq!(format_value(1.0234), "1.02");
    assert_eq!(format_value(0.05123), "0.0512");
    assert_eq!(format_value(123.4), "123");
    assert_eq!(format_value(-0.5), "-0.500");
    assert_eq!(format_value(1.5e-5), "1.50e-5");
    assert_eq!(format_value(0.0), "0");
}

#[test]
fn views_parse_with_clear_errors() {
    assert_eq!(View::parse("10,20").unwrap(), View { azimuth: 10.0, elevation: 20.0, zoom: 1.0 });
    assert_eq!(View::parse("10, 20, 2").unwrap().zoom, 2.0);
    assert!(View::parse("10").unwrap_err().contains("AZIMUTH"));
    assert!(View::parse("a,1").unwrap_err().contains("azimuth"));
    assert!(View::parse("1,1,0").unwrap_err().contains("zoom"));
}
