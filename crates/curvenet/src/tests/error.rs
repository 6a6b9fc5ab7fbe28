use super::*;

#[test]
fn ids_are_kept_for_kinds_with_a_place() {
    let e = Error::input("curve 2, sample 40: not finite").curve(2).sample(40);
    assert_eq!(e.at().curve, Some(2));
    assert_eq!(e.at().sample, Some(40));
    assert_eq!(e.kind(), "input");
    assert_eq!(e.exit_code(), 1);
    // Usage errors have no place: the ids are dropped, the message kept.
    let u = Error::usage("bad").curve(1);
    assert_eq!(u.at(), At::default());
    assert_eq!(u.to_string(), "bad");
    assert_eq!(Error::numerical("x").patch(3).at().patch, Some(3));
    assert_eq!(Error::internal("x").exit_code(), 4);
}

#[test]
fn option_names_are_respelled_by_the_front_end() {
    let e = Error::usage("give a larger `spacing` or a smaller `vertices`; see `README`");
    let cli = |name: &str| (name != "README").then(|| format!("--{}", name.replace('_', "-")));
    assert_eq!(e.spelled(&cli), "give a larger --spacing or a smaller --vertices; see `README`");
    // An unmatched backtick is left as it is.
    assert_eq!(respell("a `b", &cli), "a `b");
    assert_eq!(respell("`inner_steps`", &cli), "--inner-steps");
}
