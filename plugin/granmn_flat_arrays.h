// LAMMPS's per-atom arrays read as the flat arrays it allocates (Memory::create and grow keep
// each 2D array's rows one after the other): atom i's row of width w starts at i w of the first
// row. The pair loop and the disc integrator read them so, as LAMMPS's OPT styles do: an access
// loads no row pointer first (the arrays of row pointers of a large system also crowd the data
// cache). The wall fix does not: it visits the few atoms near a wall, where the offsets cost
// more instructions than the loads of row pointers that stay in the cache.
#ifndef GRANMN_FLAT_ARRAYS_H
#define GRANMN_FLAT_ARRAYS_H

#include <cstddef>

namespace granmn {

// The first row of a per-atom array, where the others follow; nullptr when none is allocated.
inline double *rows(double **array)
{
  return array ? array[0] : nullptr;
}

// Where atom i's row of `width` values starts, in the width of a pointer (an int offset would
// be widened again at every use).
inline std::ptrdiff_t row_start(int i, int width)
{
  return width * static_cast<std::ptrdiff_t>(i);
}

}    // namespace granmn

#endif
