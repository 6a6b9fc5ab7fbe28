//! Sparse LU with partial pivoting (faer's supernodal LU with COLAMD ordering), for the
//! non-symmetric systems: the Andrews et al. system, whose micro-Laplacians make the matrix
//! non-symmetric (\[A11\] §4.3; \[A11\] used SuperLU, also an LU).

use super::Factorization;
use faer::linalg::solvers::Solve;
use faer::sparse::{SparseColMat, Triplet};
use faer::MatMut;

/// Why an LU factorisation failed.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum LuError {
    /// The triplets do not form an `n × n` matrix (an index out of range); faer's message.
    Assembly(String),
    /// A pivot vanished: the matrix is singular; faer's message.
    Singular(String),
}

/// A factorisation `P A Q = L U` of a square sparse matrix, reused for every right-hand side.
pub struct Lu {
    lu: faer::sparse::linalg::solvers::Lu<usize, f64>,
    n: usize,
}

impl Lu {
    /// Factorises the `n × n` matrix given as `(row, column, value)` triplets (repeated
    /// entries are summed).
    pub fn factor(n: usize, triplets: &[(u32, u32, f64)]) -> std::result::Result<Self, LuError> {
        let trip: Vec<Triplet<usize, usize, f64>> =
            triplets.iter().map(|&(r, c, x)| Triplet::new(r as usize, c as usize, x)).collect();
        let a = SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &trip)
            .map_err(|e| LuError::Assembly(format!("{e:?}")))?;
        let lu = a.sp_lu().map_err(|e| LuError::Singular(format!("{e:?}")))?;
        Ok(Lu { lu, n })
    }
}

impl Factorization for Lu {
    fn dim(&self) -> usize {
        self.n
    }

    fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        self.lu.solve_in_place(rhs);
    }
}
