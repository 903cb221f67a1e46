//! Ensembles across the ranks of an MPI communicator (feature `mpi`): the chunks of a reduction are
//! split in contiguous blocks, one per rank; each rank runs its block with rayon; rank 0 gathers the
//! chunk accumulators (as bytes, [`Wire`]) and merges them in the same fixed tree as
//! [`Ensemble::reduce`], so the result is bit-identical to the one-machine run.

use crate::{reduce, Ensemble, Error, Failure, Members, Reduced, Reducer, Result, Runs, Wire};
use mpi::datatype::PartitionMut;
use mpi::traits::{Communicator, Root};
use mpi::Count;

/// The chunks (or members) `[n r / size, n (r + 1) / size)` of rank `r`: contiguous blocks that cover
/// 0..n in rank order, of sizes that differ by at most one.
pub(crate) fn block(n: usize, rank: usize, size: usize) -> std::ops::Range<usize> {
    let at = |r: usize| ((n as u128 * r as u128) / size.max(1) as u128) as usize;
    at(rank)..at(rank + 1)
}

impl<T: Wire, E: Wire> Wire for std::result::Result<T, E> {
    fn encode(&self, out: &mut Vec<u8>) {
        self.is_ok().encode(out);
        match self {
            Ok(t) => t.encode(out),
            Err(e) => e.encode(out),
        }
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        Ok(if bool::decode(input)? {
            Ok(T::decode(input)?)
        } else {
            Err(E::decode(input)?)
        })
    }
}

impl<M: Members, F> Ensemble<M, F> {
    /// [`reduce`](Self::reduce) across the ranks of `comm`: every rank must call it (with the same
    /// ensemble); rank 0 gets `Some` of the result, bit-identical to `reduce` on one machine, the other
    /// ranks `None`. Failed members come back with their error as text.
    pub fn reduce_mpi<S, E, R, C>(&self, comm: &C, reducer: &R) -> Result<Option<Reduced<R::Acc, String>>>
    where
        F: Fn(usize, &M::Param) -> std::result::Result<S, E> + Sync,
        R: Reducer<S>,
        R::Acc: Wire,
        E: Send + std::fmt::Display,
        C: Communicator,
    {
        let (rank, size) = rank_size(comm)?;
        let (accs, failures) = self.fold_chunks(reducer, block(self.chunks(), rank, size));
        let mut buf = Vec::new();
        (self.members().len(), self.chunk()).encode(&mut buf);
        accs.encode(&mut buf);
        failures
            .into_iter()
            .map(|f| (f.index, f.error.to_string()))
            .collect::<Vec<_>>()
            .encode(&mut buf);
        let Some(messages) = gather_bytes(comm, &buf)? else {
            return Ok(None);
        };
        let mut all_accs = Vec::with_capacity(self.chunks());
        let mut all_failures = Vec::new();
        for (r, msg) in messages.iter().enumerate() {
            let mut input = msg.as_slice();
            self.check_same(r, <(usize, usize)>::decode(&mut input)?)?;
            all_accs.extend(Vec::<R::Acc>::decode(&mut input)?);
            all_failures.extend(
                Vec::<(usize, String)>::decode(&mut input)?
                    .into_iter()
                    .map(|(index, error)| Failure { index, error }),
            );
        }
        if all_accs.len() != self.chunks() {
            return Err(Error::Mpi(format!(
                "{} chunk accumulators gathered, {} expected",
                all_accs.len(),
                self.chunks()
            )));
        }
        Ok(Some(Reduced {
            value: reduce::tree(reducer, all_accs),
            failures: all_failures,
            members: self.members().len(),
        }))
    }

    /// [`run`](Self::run) across the ranks of `comm`: every rank must call it; members are split in
    /// contiguous blocks, and rank 0 gets every member's result in member order (errors as text), the
    /// other ranks `None`.
    pub fn run_mpi<S, E, C>(&self, comm: &C) -> Result<Option<Runs<S, String>>>
    where
        F: Fn(usize, &M::Param) -> std::result::Result<S, E> + Sync,
        S: Send + Wire,
        E: Send + std::fmt::Display,
        C: Communicator,
    {
        let (rank, size) = rank_size(comm)?;
        let mine = self.run_range(block(self.members().len(), rank, size));
        let mut buf = Vec::new();
        (self.members().len(), self.chunk()).encode(&mut buf);
        mine.into_iter()
            .map(|r| r.map_err(|e| e.to_string()))
            .collect::<Vec<_>>()
            .encode(&mut buf);
        let Some(messages) = gather_bytes(comm, &buf)? else {
            return Ok(None);
        };
        let mut results = Vec::with_capacity(self.members().len());
        for (r, msg) in messages.iter().enumerate() {
            let mut input = msg.as_slice();
            self.check_same(r, <(usize, usize)>::decode(&mut input)?)?;
            results.extend(Vec::<std::result::Result<S, String>>::decode(&mut input)?);
        }
        if results.len() != self.members().len() {
            return Err(Error::Mpi(format!(
                "{} results gathered, {} expected",
                results.len(),
                self.members().len()
            )));
        }
        Ok(Some(Runs { results }))
    }

    /// Checks that rank `r` ran the same ensemble (members, chunk size) as rank 0.
    fn check_same(&self, r: usize, (n, chunk): (usize, usize)) -> Result<()> {
        if (n, chunk) != (self.members().len(), self.chunk()) {
            return Err(Error::Mpi(format!(
                "rank {r} has {n} members in chunks of {chunk}, rank 0 has {} in chunks of {}",
                self.members().len(),
                self.chunk()
            )));
        }
        Ok(())
    }
}

fn rank_size<C: Communicator>(comm: &C) -> Result<(usize, usize)> {
    let rank = usize::try_from(comm.rank()).map_err(|_| Error::Mpi("negative rank".into()))?;
    let size = usize::try_from(comm.size()).map_err(|_| Error::Mpi("negative size".into()))?;
    Ok((rank, size))
}

/// Gathers every rank's bytes on rank 0 (in rank order); `None` on the other ranks.
fn gather_bytes<C: Communicator>(comm: &C, buf: &[u8]) -> Result<Option<Vec<Vec<u8>>>> {
    let root = comm.process_at_rank(0);
    let len = Count::try_from(buf.len()).map_err(|_| Error::Mpi("a rank's message exceeds 2 GiB".into()))?;
    if comm.rank() != 0 {
        root.gather_into(&len);
        root.gather_varcount_into(buf);
        return Ok(None);
    }
    let (_, size) = rank_size(comm)?;
    let mut counts: Vec<Count> = vec![0; size];
    root.gather_into_root(&len, &mut counts[..]);
    let mut displs: Vec<Count> = Vec::with_capacity(size);
    let mut total: Count = 0;
    for &c in &counts {
        displs.push(total);
        total = total
            .checked_add(c)
            .ok_or_else(|| Error::Mpi("the gathered messages exceed 2 GiB".into()))?;
    }
    let mut all = vec![0u8; total as usize];
    {
        let mut partition = PartitionMut::new(&mut all[..], &counts[..], &displs[..]);
        root.gather_varcount_into_root(buf, &mut partition);
    }
    Ok(Some(
        counts
            .iter()
            .zip(&displs)
            .map(|(&c, &d)| all[d as usize..(d + c) as usize].to_vec())
            .collect(),
    ))
}
