//! `jointid merge`: the shard files of `study --shard K/N` into the study's result CSV.

use anyhow::Context;

use crate::cli::MergeArgs;
use jointid::cluster::{ShardFile, merge};
use jointid::output::{check_outputs, write_atomically};

/// Reads every shard, checks and merges them in memory, then writes the CSV whole: on any
/// error nothing is written.
pub fn run(args: &MergeArgs) -> anyhow::Result<()> {
    let inputs: Vec<&std::path::Path> = args.shards.iter().map(|p| p.as_path()).collect();
    check_outputs(&[args.out.as_path()], &inputs)?;
    let shards = args
        .shards
        .iter()
        .map(|p| ShardFile::from_path(p))
        .collect::<Result<Vec<_>, _>>()?;
    let bytes = merge(&shards)?;
    if let Some(dir) = args.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        jointid::output::atomic::create_folders(dir)
            .with_context(|| format!("{}: cannot create the directory", dir.display()))?;
    }
    write_atomically(&args.out, |w| w.write_all(&bytes))
        .with_context(|| format!("{}: cannot write", args.out.display()))?;
    let h = &shards[0].header;
    super::to_stdout(|w| {
        writeln!(
            w,
            "{}: {} shard file(s) of {} ({} cells, fingerprint {}) merged",
            args.out.display(),
            shards.len(),
            h.study,
            h.assignment.len(),
            h.fingerprint
        )
    })
}
