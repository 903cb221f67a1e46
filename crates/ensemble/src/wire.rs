//! How accumulators and outputs cross between MPI ranks: as bytes, little-endian, floats bit for bit
//! (so a merge on rank 0 sees exactly the numbers the other rank computed).

use crate::{Counts, Error, Moments, Result};

/// A value that can be sent to another rank as bytes and read back unchanged (bit for bit).
pub trait Wire: Sized {
    /// Appends the bytes of `self` to `out`.
    fn encode(&self, out: &mut Vec<u8>);
    /// Reads one value from the front of `input` and advances it.
    fn decode(input: &mut &[u8]) -> Result<Self>;
}

fn take<'a>(input: &mut &'a [u8], n: usize) -> Result<&'a [u8]> {
    if input.len() < n {
        return Err(Error::Decode("message ends early"));
    }
    let (head, tail) = input.split_at(n);
    *input = tail;
    Ok(head)
}

fn array8(input: &mut &[u8]) -> Result<[u8; 8]> {
    let mut a = [0u8; 8];
    a.copy_from_slice(take(input, 8)?);
    Ok(a)
}

impl Wire for u64 {
    fn encode(&self, out: &mut Vec<u8>) {
        out.extend_from_slice(&self.to_le_bytes());
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        Ok(u64::from_le_bytes(array8(input)?))
    }
}

impl Wire for usize {
    fn encode(&self, out: &mut Vec<u8>) {
        (*self as u64).encode(out);
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        usize::try_from(u64::decode(input)?).map_err(|_| Error::Decode("index does not fit in usize"))
    }
}

impl Wire for f64 {
    fn encode(&self, out: &mut Vec<u8>) {
        self.to_bits().encode(out);
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        Ok(f64::from_bits(u64::decode(input)?))
    }
}

impl Wire for bool {
    fn encode(&self, out: &mut Vec<u8>) {
        out.push(u8::from(*self));
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        match take(input, 1)?[0] {
            0 => Ok(false),
            1 => Ok(true),
            _ => Err(Error::Decode("a bool is 0 or 1")),
        }
    }
}

impl Wire for String {
    fn encode(&self, out: &mut Vec<u8>) {
        self.len().encode(out);
        out.extend_from_slice(self.as_bytes());
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        let n = usize::decode(input)?;
        String::from_utf8(take(input, n)?.to_vec()).map_err(|_| Error::Decode("a string is not UTF-8"))
    }
}

impl<T: Wire> Wire for Vec<T> {
    fn encode(&self, out: &mut Vec<u8>) {
        self.len().encode(out);
        for x in self {
            x.encode(out);
        }
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        let n = usize::decode(input)?;
        // Each element takes at least one byte: a corrupt length cannot make us allocate wildly.
        if n > input.len() {
            return Err(Error::Decode("a vector longer than the message"));
        }
        (0..n).map(|_| T::decode(input)).collect()
    }
}

impl<T: Wire> Wire for Option<T> {
    fn encode(&self, out: &mut Vec<u8>) {
        self.is_some().encode(out);
        if let Some(x) = self {
            x.encode(out);
        }
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        Ok(if bool::decode(input)? {
            Some(T::decode(input)?)
        } else {
            None
        })
    }
}

impl<A: Wire, B: Wire> Wire for (A, B) {
    fn encode(&self, out: &mut Vec<u8>) {
        self.0.encode(out);
        self.1.encode(out);
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        Ok((A::decode(input)?, B::decode(input)?))
    }
}

impl<A: Wire, B: Wire, C: Wire> Wire for (A, B, C) {
    fn encode(&self, out: &mut Vec<u8>) {
        self.0.encode(out);
        self.1.encode(out);
        self.2.encode(out);
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        Ok((A::decode(input)?, B::decode(input)?, C::decode(input)?))
    }
}

impl Wire for Counts {
    fn encode(&self, out: &mut Vec<u8>) {
        self.counts.encode(out);
        self.below.encode(out);
        self.above.encode(out);
        self.nan.encode(out);
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        Ok(Counts {
            counts: Vec::decode(input)?,
            below: u64::decode(input)?,
            above: u64::decode(input)?,
            nan: u64::decode(input)?,
        })
    }
}

impl Wire for Moments {
    fn encode(&self, out: &mut Vec<u8>) {
        self.n.encode(out);
        self.mean.encode(out);
        self.m2.encode(out);
    }
    fn decode(input: &mut &[u8]) -> Result<Self> {
        Ok(Moments {
            n: u64::decode(input)?,
            mean: f64::decode(input)?,
            m2: f64::decode(input)?,
        })
    }
}
