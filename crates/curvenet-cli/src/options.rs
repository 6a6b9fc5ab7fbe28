//! The surfacing options shared by `surface`, `study` and `bench`: one flag per entry of the
//! library's option table ([`curvenet::pipeline::OPTIONS`]), `--name` with dashes for
//! underscores, with its help and default from the table. The flags are built from the table,
//! not listed here, so the command line cannot drift from the library or from Python.

use clap::{Arg, ArgAction, ArgMatches, Args, Command, FromArgMatches};
use curvenet::pipeline::OPTIONS;
use curvenet::{Error, Options, Preset};

/// The options of a surfacing run as given on the command line: a preset and the flags given
/// explicitly (the others keep the preset's values).
#[derive(Clone, Debug, Default)]
pub struct SolveArgs {
    /// `--preset`, `--fast` or `--paper`.
    pub preset: Preset,
    /// `(option name, value)` of each flag given, in the order of the table.
    pub given: Vec<(&'static str, String)>,
}

/// The flag of option `name`: `inner_steps` → `inner-steps`.
pub fn flag(name: &str) -> String {
    name.replace('_', "-")
}

/// `text` with the option names in backticks as flags (`` `spacing` `` → `--spacing`), other
/// backticked words without their backticks.
fn spelled(text: &str) -> String {
    let flags = curvenet::error::respell(text, &|name| {
        OPTIONS.iter().any(|s| s.name == name).then(|| format!("--{}", flag(name)))
    });
    flags.replace('`', "")
}

/// The library options the flags select: the preset, then every flag given.
pub fn options(a: &SolveArgs) -> Result<Options, Error> {
    let given: Vec<(&str, &str)> = a.given.iter().map(|(n, v)| (*n, v.as_str())).collect();
    Options::from_named(a.preset, &given)
}

impl FromArgMatches for SolveArgs {
    fn from_arg_matches(m: &ArgMatches) -> Result<Self, clap::Error> {
        let mut out = SolveArgs::default();
        out.update_from_arg_matches(m)?;
        Ok(out)
    }

    fn update_from_arg_matches(&mut self, m: &ArgMatches) -> Result<(), clap::Error> {
        self.preset = if m.get_flag("fast") {
            Preset::Fast
        } else if m.get_flag("paper") {
            Preset::Paper
        } else {
            match m.get_one::<String>("preset") {
                Some(p) => {
                    Preset::from_name(p).map_err(|e| clap::Error::raw(clap::error::ErrorKind::InvalidValue, e))?
                }
                None => Preset::Default,
            }
        };
        self.given.clear();
        for spec in OPTIONS {
            if let Some(v) = m.get_one::<String>(spec.name) {
                self.given.push((spec.name, v.clone()));
            }
        }
        Ok(())
    }
}

impl Args for SolveArgs {
    fn augment_args(cmd: Command) -> Command {
        let mut cmd = cmd
            .arg(Arg::new("preset").long("preset").value_name("NAME").value_parser(["default", "fast", "paper"]).help(
                "Starting values of the options below: default (conformal patching and 3D iterations), \
                         fast (planar patching, no iteration: one factorisation) or paper (the paper as written); \
                         the options given explicitly override it",
            ))
            .arg(
                Arg::new("fast")
                    .long("fast")
                    .action(ArgAction::SetTrue)
                    .conflicts_with_all(["paper", "preset"])
                    .help("Same as --preset fast"),
            )
            .arg(
                Arg::new("paper")
                    .long("paper")
                    .action(ArgAction::SetTrue)
                    .conflicts_with("preset")
                    .help("Same as --preset paper"),
            );
        for spec in OPTIONS {
            let mut arg = Arg::new(spec.name)
                .long(flag(spec.name))
                .value_name(spec.value_name)
                .num_args(1)
                .allow_negative_numbers(true)
                .help(format!("{} [default: {}]", spelled(spec.help), spelled(&spec.default_text())));
            if !spec.choices.is_empty() {
                arg = arg.value_parser(clap::builder::PossibleValuesParser::new(spec.choices.iter().copied()));
            }
            for alias in spec.aliases {
                arg = arg.alias(*alias);
            }
            if spec.name == "spacing" {
                arg = arg.conflicts_with("vertices");
            }
            if spec.name == "infer_normals" {
                // `--infer-normals` alone: re-infer every curve's normals.
                arg = arg.num_args(0..=1).default_missing_value("all").require_equals(true);
            }
            cmd = cmd.arg(arg);
        }
        cmd
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}
