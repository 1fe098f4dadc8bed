#include "fix_per_atom_state.h"

#include "atom.h"
#include "error.h"
#include "memory.h"

using namespace LAMMPS_NS;

void FixPerAtomState::register_state(int columns)
{
  ncols = columns;
  restart_peratom = 1;
  wd_header = columns > 0;    // only to say, when write_data runs, that the state is not in it
  create_attribute = 1;
  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  has_callbacks = true;
  for (int i = 0; i < atom->nlocal; i++) set_arrays(i);
}

void FixPerAtomState::widen_state(int columns)
{
  if (columns <= ncols) return;
  if (!has_callbacks)
    error->all(FLERR, "Fix {} ({}): per-atom state widened without register_state in the "
                      "constructor", id, style);
  double **wider = nullptr;
  memory->create(wider, atom->nmax, columns, "fix:per-atom state");
  for (int i = 0; i < atom->nmax; i++)
    for (int k = 0; k < columns; k++) wider[i][k] = k < ncols ? state[i][k] : 0.0;
  memory->destroy(state);
  state = wider;
  ncols = columns;
  wd_header = 1;
}

// Called by write_data (on its writing process): writes nothing, warns that the per-atom state
// (contact history, previous accelerations) will not come back from the data file.
void FixPerAtomState::write_data_header(FILE *, int)
{
  error->warning(FLERR,
                 "write_data does not carry the per-atom state of fix {} ({}): a run from "
                 "read_data starts it afresh; use write_restart to continue exactly",
                 id, style);
}

FixPerAtomState::~FixPerAtomState()
{
  if (has_callbacks) {
    atom->delete_callback(id, Atom::GROW);
    atom->delete_callback(id, Atom::RESTART);
  }
  memory->destroy(state);
}

double FixPerAtomState::memory_usage()
{
  return (double) atom->nmax * ncols * sizeof(double);
}

void FixPerAtomState::grow_arrays(int nmax)
{
  memory->grow(state, nmax, ncols, "fix:per-atom state");
}

void FixPerAtomState::copy_arrays(int i, int j, int)
{
  for (int k = 0; k < ncols; k++) state[j][k] = state[i][k];
}

void FixPerAtomState::set_arrays(int i)
{
  for (int k = 0; k < ncols; k++) state[i][k] = 0.0;
}

int FixPerAtomState::pack_exchange(int i, double *buf)
{
  for (int k = 0; k < ncols; k++) buf[k] = state[i][k];
  return ncols;
}

int FixPerAtomState::unpack_exchange(int nlocal, double *buf)
{
  for (int k = 0; k < ncols; k++) state[nlocal][k] = buf[k];
  return ncols;
}

int FixPerAtomState::pack_restart(int i, double *buf)
{
  buf[0] = ncols + 1;    // count including itself, as the per-atom restart layout requires
  return 1 + pack_exchange(i, &buf[1]);
}

// The record holds as many columns as the writing run had: read those (widening the state if
// they are more), never past the record.
void FixPerAtomState::unpack_restart(int nlocal, int nth)
{
  int stored = 0;
  const double *written = restart_row(nlocal, nth, stored);
  widen_state(stored);
  for (int k = 0; k < ncols; k++) state[nlocal][k] = k < stored ? written[k] : 0.0;
}

const double *FixPerAtomState::restart_row(int nlocal, int nth, int &stored) const
{
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[nlocal][m]);
  stored = static_cast<int>(extra[nlocal][m]) - 1;
  return &extra[nlocal][m + 1];
}

int FixPerAtomState::size_restart(int)
{
  return ncols + 1;
}

int FixPerAtomState::maxsize_restart()
{
  return ncols + 1;
}
