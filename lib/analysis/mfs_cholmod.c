#include "mfs_cholmod.h"
#include "mfs_alloc.h"

#include <math.h>
#include <string.h>

void mfs_cholmod_start(cholmod_common *c)
{
  cholmod_l_start(c);
  c->print = 0; /* the library never prints */
  c->error_handler = NULL;
}

cholmod_sparse *mfs_cholmod_upper(const mfs_csr *A, cholmod_common *c)
{
  size_t n = A->nrow, nnz = 0;
  for (size_t j = 0; j < n; j++)
    for (size_t e = A->ptr[j]; e < A->ptr[j + 1]; e++)
      nnz += (size_t)A->idx[e] <= j;
  cholmod_sparse *S = cholmod_l_allocate_sparse(n, n, nnz, 0, 1, 1, CHOLMOD_REAL, c);
  if (!S)
    return NULL;
  SuiteSparse_long *Sp = S->p, *Si = S->i;
  double *Sx = S->x;
  size_t pos = 0;
  Sp[0] = 0;
  for (size_t j = 0; j < n; j++) {
    for (size_t e = A->ptr[j]; e < A->ptr[j + 1]; e++)
      if ((size_t)A->idx[e] <= j) {
        Si[pos] = A->idx[e];
        Sx[pos++] = A->val[e];
      }
    Sp[j + 1] = (SuiteSparse_long)pos;
  }
  if (!cholmod_l_sort(S, c)) {
    cholmod_l_free_sparse(&S, c);
    return NULL;
  }
  return S;
}

/* ---- a geometric nested dissection ---------------------------------- */

/* Key of unknown v along axis k: its coordinate, ties by index. */
static int key_less(const double *x, int dim, int k, SuiteSparse_long a, SuiteSparse_long b)
{
  double xa = x[(size_t)a * (size_t)dim + (size_t)k], xb = x[(size_t)b * (size_t)dim + (size_t)k];
  return xa < xb || (xa == xb && a < b);
}

static void swap_long(SuiteSparse_long *a, SuiteSparse_long *b)
{
  SuiteSparse_long t = *a;
  *a = *b;
  *b = t;
}

/* Rearrange v[0..n) so that v[m] is the m-th by key and the ones before it
 * are not greater, the ones after not smaller (quickselect, median of three). */
static void select_kth(SuiteSparse_long *v, size_t n, size_t m, const double *x, int dim, int k)
{
  size_t lo = 0, hi = n - 1;
  while (hi > lo) {
    size_t mid = lo + (hi - lo) / 2; /* the median of v[lo], v[mid], v[hi] into v[mid] */
    if (key_less(x, dim, k, v[mid], v[lo]))
      swap_long(v + mid, v + lo);
    if (key_less(x, dim, k, v[hi], v[mid])) {
      swap_long(v + mid, v + hi);
      if (key_less(x, dim, k, v[mid], v[lo]))
        swap_long(v + mid, v + lo);
    }
    SuiteSparse_long piv = v[mid];
    size_t i = lo, j = hi;
    while (i <= j) { /* Hoare partition around the pivot's key (keys are distinct) */
      while (key_less(x, dim, k, v[i], piv))
        i++;
      while (key_less(x, dim, k, piv, v[j]))
        j--;
      if (i <= j) {
        swap_long(v + i, v + j);
        i++;
        if (j == 0)
          break;
        j--;
      }
    }
    if (m <= j)
      hi = j;
    else if (m >= i)
      lo = i;
    else
      return;
  }
}

int mfs_cholmod_geometric_order(size_t n, const mfs_csr *A, const mfs_csr *B, const double *x,
                                int dim, SuiteSparse_long *perm)
{
  enum { LEAF = 64, STACK = 128 }; /* STACK: 2 entries a part, 2 parts a level, 32 levels */
  int ok = 0;
  unsigned char *side = mfs_calloc(n ? n : 1, 1);
  SuiteSparse_long *tmp = mfs_malloc((n ? n : 1) * sizeof *tmp);
  size_t *stack = mfs_malloc(STACK * sizeof *stack);
  if (!side || !tmp || !stack)
    goto done;
  for (size_t i = 0; i < n; i++)
    perm[i] = (SuiteSparse_long)i;
  size_t top = 0;
  stack[top++] = 0;
  stack[top++] = n;
  while (top > 0) {
    size_t hi = stack[--top], lo = stack[--top], len = hi - lo;
    if (len <= LEAF)
      continue;
    SuiteSparse_long *v = perm + lo;
    /* the longer extent of the part's box */
    int axis = 0;
    double ext = -1.0;
    for (int k = 0; k < dim; k++) {
      double a = INFINITY, b = -INFINITY;
      for (size_t t = 0; t < len; t++) {
        double c = x[(size_t)v[t] * (size_t)dim + (size_t)k];
        a = c < a ? c : a;
        b = c > b ? c : b;
      }
      if (b - a > ext) {
        ext = b - a;
        axis = k;
      }
    }
    size_t half = len / 2;
    select_kth(v, len, half, x, dim, axis);
    for (size_t t = 0; t < len; t++)
      side[v[t]] = t < half ? 1 : 2;
    /* the separator: the left unknowns coupled to a right one (in A or B) */
    size_t nl = 0, ns = 0;
    for (size_t t = 0; t < half; t++) {
      SuiteSparse_long u = v[t];
      int sep = 0;
      for (size_t e = A->ptr[u]; e < A->ptr[u + 1] && !sep; e++)
        sep = side[A->idx[e]] == 2;
      if (B)
        for (size_t e = B->ptr[u]; e < B->ptr[u + 1] && !sep; e++)
          sep = side[B->idx[e]] == 2;
      if (sep)
        tmp[len - 1 - ns++] = u; /* from the back: the separator last */
      else
        tmp[nl++] = u;
    }
    size_t nr = len - half;
    for (size_t t = 0; t < nr; t++)
      tmp[nl + t] = v[half + t];
    /* tmp[len - ns .. len) holds the separator reversed: any order will do */
    for (size_t t = 0; t < len; t++)
      side[v[t]] = 0;
    memcpy(v, tmp, len * sizeof *v);
    if (top + 4 <= STACK) { /* the parts halve: 32 levels are 2^32 times LEAF unknowns */
      stack[top++] = lo;
      stack[top++] = lo + nl;
      stack[top++] = lo + nl;
      stack[top++] = lo + nl + nr;
    }
  }
  ok = 1;
done:
  mfs_free(side);
  mfs_free(tmp);
  mfs_free(stack);
  return ok;
}
