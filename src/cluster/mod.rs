//! Studies on a cluster: a study split by cells into N shards that run anywhere, each a file
//! that carries the study's fingerprint, merged back into exactly the bytes of the
//! single-machine result; and the Slurm scripts that run the shards as a job array.
//!
//! A cell gives the same bits wherever it runs: every trial draws from its own stream seeded
//! by (seed, cell, trial) ([`crate::random`]), and a cell's statistics depend on its
//! trials alone. So the split changes no number, only where it is computed.
//!
//! - [`shard`]: `K/N`, the estimated cost of a cell and the balanced assignment;
//! - [`shard_file`]: the shard result file (it carries the study's fingerprint,
//!   [`crate::study::fingerprint`], and the hash of its rows);
//! - [`shard_rows`]: every row of a shard checked (fields, finite numbers, a cell's keys);
//! - [`mod@merge`]: the checks and the merged CSV;
//! - [`results`]: a result CSV read back for `check --results`;
//! - [`slurm`]: the sbatch job array, the dependent merge job and the submit script;
//! - [`shell`]: the character sets of every value a script holds, and its one quoting routine.
//!
//! Layer 6 (diagnosis and results; see the crate docs): may import the layers below
//! ([`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`],
//! [`crate::modal`], [`crate::model`], [`crate::measured`], [`crate::extract`],
//! [`crate::identify`], [`crate::simulate`], [`crate::study`]) and, without a circle,
//! [`crate::diagnose`], [`crate::report`].

pub mod merge;
pub mod results;
pub mod shard;
pub mod shard_file;
pub mod shard_rows;
pub mod shell;
pub mod slurm;

pub use merge::{MergeError, merge};
pub use results::{ResultsError, read_results, read_results_path};
pub use shard::{ShardError, ShardSpec, assign, cell_cost, study_assignment};
pub use shard_file::{ShardFile, ShardFileError, ShardHeader, write_shard};
pub use slurm::{SlurmPlan, SlurmScripts, check_settings};
