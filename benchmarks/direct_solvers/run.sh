#!/usr/bin/env bash
# The direct factorisations on one matrix (doc/transient.md, "The direct
# solver is a Cholesky factorisation"): compiles factorisations.cc and
# factorises MATRIX.mtx (MatrixMarket, coordinate, real, both triangles) on
# one core with each of SuiteSparse's solvers.
#
# The matrix quoted in doc/transient.md is the 2D transient example's at
# step 4 (second active set), 138 774 rows. It was written by a temporary
# call, not committed, to EpetraExt::RowMatrixToMatrixMarketFile(file,
# system_matrix.trilinos_matrix()) just before the direct factorisation in
# LinearElasticity::setup_preconditioner(), with the example cut at step 4.
#
# usage: bash benchmarks/direct_solvers/run.sh MATRIX.mtx [WORK_DIR]
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
matrix=${1:?usage: run.sh MATRIX.mtx [WORK_DIR]}
work=${2:-/tmp/cycloid-direct-solvers}
mkdir -p "$work"
g++ -O2 -o "$work/factorisations" "$here/factorisations.cc" \
  -lcholmod -lklu -lumfpack -lamd -lcolamd -lsuitesparseconfig
"$work/factorisations" "$matrix"
