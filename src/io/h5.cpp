#include "fsi/io/h5.hpp"

#include <algorithm>
#include <hdf5.h>
#include <numeric>

namespace fsi {

H5File::H5File(const std::string &path, Mode mode) : path_(path) {
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); // we report errors ourselves
  id_ = mode == create ? H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)
                       : H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (id_ >= 0) return;
  if (mode == create)
    throw OutputError("cannot create HDF5 file '" + path +
                      "' (is the directory writable, the disk full?)");
  throw InputError("cannot open HDF5 file '" + path +
                   "' (missing, or not an HDF5 file: a corrupt or partial write?)");
}

void H5File::close() {
  if (id_ < 0) return;
  const herr_t e = H5Fclose(id_); // flushes what HDF5 still holds: a full disk shows here
  id_ = -1;
  if (e < 0) throw OutputError("cannot finish writing '" + path_ + "' (disk full?)");
}

H5File::~H5File() {
  if (id_ >= 0) H5Fclose(id_);
}

void H5File::flush() {
  if (H5Fflush(id_, H5F_SCOPE_GLOBAL) < 0)
    throw OutputError("cannot write '" + path_ + "' (disk full?)");
}

void H5File::make_groups(const std::string &name) {
  for (size_t p = name.find('/', 1); p != std::string::npos; p = name.find('/', p + 1)) {
    const std::string g = name.substr(0, p);
    if (H5Lexists(id_, g.c_str(), H5P_DEFAULT) > 0) continue;
    hid_t gid = H5Gcreate2(id_, g.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    if (gid < 0) throw OutputError("cannot create group " + g + " in '" + path_ + "' (disk full?)");
    H5Gclose(gid);
  }
}

static void write_raw(long file, const std::string &path, const std::string &name, hid_t type,
                      const void *data, size_t n, size_t cols) {
  hsize_t dims[2] = {cols ? n / cols : 0, cols};
  hid_t space = H5Screate_simple(cols > 1 ? 2 : 1, dims, nullptr);
  if (H5Lexists(file, name.c_str(), H5P_DEFAULT) > 0) H5Ldelete(file, name.c_str(), H5P_DEFAULT);
  hid_t ds = H5Dcreate2(file, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok =
      ds >= 0 && (n == 0 || H5Dwrite(ds, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) >= 0);
  if (ds >= 0) H5Dclose(ds);
  H5Sclose(space);
  if (!ok) throw OutputError("cannot write " + name + " to '" + path + "' (disk full?)");
}

void H5File::write(const std::string &name, const std::vector<double> &v, size_t cols) {
  make_groups(name);
  write_raw(id_, path_, name, H5T_NATIVE_DOUBLE, v.data(), v.size(), cols);
}

void H5File::write_ints(const std::string &name, const std::vector<long> &v, size_t cols) {
  make_groups(name);
  write_raw(id_, path_, name, H5T_NATIVE_LONG, v.data(), v.size(), cols);
}

bool H5File::has(const std::string &name) const {
  return H5Lexists(id_, name.c_str(), H5P_DEFAULT) > 0;
}

std::vector<double> H5File::read(const std::string &name) const {
  if (!has(name)) throw InputError("'" + path_ + "' has no dataset " + name);
  hid_t ds = H5Dopen2(id_, name.c_str(), H5P_DEFAULT);
  hid_t space = H5Dget_space(ds);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  std::vector<double> v(n);
  const bool ok =
      n == 0 || H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()) >= 0;
  H5Sclose(space);
  H5Dclose(ds);
  if (!ok) throw InputError("cannot read " + name + " from '" + path_ + "' (corrupt file?)");
  return v;
}

void H5File::set(const std::string &attr, double v) {
  if (H5Aexists(id_, attr.c_str()) > 0) H5Adelete(id_, attr.c_str());
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(id_, attr.c_str(), H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = a >= 0 && H5Awrite(a, H5T_NATIVE_DOUBLE, &v) >= 0;
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
  if (!ok) throw OutputError("cannot write attribute " + attr + " to '" + path_ + "' (disk full?)");
}

void H5File::set(const std::string &attr, const std::string &v) {
  if (H5Aexists(id_, attr.c_str()) > 0) H5Adelete(id_, attr.c_str());
  hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, v.size() + 1);
  hid_t space = H5Screate(H5S_SCALAR);
  hid_t a = H5Acreate2(id_, attr.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT);
  const bool ok = a >= 0 && H5Awrite(a, type, v.c_str()) >= 0;
  if (a >= 0) H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
  if (!ok) throw OutputError("cannot write attribute " + attr + " to '" + path_ + "' (disk full?)");
}

double H5File::get(const std::string &attr) const {
  if (H5Aexists(id_, attr.c_str()) <= 0)
    throw InputError("'" + path_ + "' has no attribute " + attr + " (not an fsi_app file?)");
  double v = 0;
  hid_t a = H5Aopen(id_, attr.c_str(), H5P_DEFAULT);
  const bool ok = a >= 0 && H5Aread(a, H5T_NATIVE_DOUBLE, &v) >= 0;
  if (a >= 0) H5Aclose(a);
  if (!ok)
    throw InputError("cannot read attribute " + attr + " from '" + path_ + "' (corrupt file?)");
  return v;
}

bool H5File::has_attribute(const std::string &attr) const {
  return H5Aexists(id_, attr.c_str()) > 0;
}

std::string H5File::get_string(const std::string &attr) const {
  if (H5Aexists(id_, attr.c_str()) <= 0)
    throw InputError("'" + path_ + "' has no attribute " + attr + " (not an fsi_app file?)");
  hid_t a = H5Aopen(id_, attr.c_str(), H5P_DEFAULT);
  hid_t type = H5Aget_type(a);
  std::string s(H5Tget_size(type), '\0');
  H5Aread(a, type, s.data());
  H5Tclose(type);
  H5Aclose(a);
  s.resize(s.find('\0') == std::string::npos ? s.size() : s.find('\0'));
  return s;
}

static bool key_less(const double *a, const double *b, int kdim) {
  return std::lexicographical_compare(a, a + kdim, b, b + kdim);
}

KeyedItems gather_sorted(MPI_Comm comm, const std::vector<double> &keys,
                         const std::vector<double> &values, int kdim, int vdim) {
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int n = (int)(keys.size() / kdim);
  std::vector<int> counts(size), displ(size);
  MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm);
  KeyedItems all, out;
  auto gatherv = [&](const std::vector<double> &local, std::vector<double> &dest, int dim) {
    std::vector<int> c(size), d(size);
    long total = 0;
    for (int r = 0; r < size; ++r) {
      c[r] = counts[r] * dim;
      d[r] = (int)total;
      total += c[r];
    }
    if (rank == 0) dest.resize(total);
    MPI_Gatherv(local.data(), n * dim, MPI_DOUBLE, dest.data(), c.data(), d.data(), MPI_DOUBLE, 0,
                comm);
  };
  gatherv(keys, all.keys, kdim);
  gatherv(values, all.values, vdim);
  if (rank != 0) return out;
  sort_items(all, kdim, vdim);
  return all;
}

void sort_items(KeyedItems &items, int kdim, int vdim) {
  const size_t N = items.keys.size() / kdim;
  std::vector<size_t> idx(N);
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) {
    return key_less(&items.keys[a * kdim], &items.keys[b * kdim], kdim);
  });
  KeyedItems out;
  out.keys.resize(items.keys.size());
  out.values.resize(items.values.size());
  for (size_t i = 0; i < N; ++i) {
    std::copy_n(&items.keys[idx[i] * kdim], kdim, &out.keys[i * kdim]);
    std::copy_n(&items.values[idx[i] * vdim], vdim, &out.values[i * vdim]);
  }
  items = std::move(out);
}

long find_key(const KeyedItems &items, const double *k, int kdim) {
  const long N = (long)(items.keys.size() / kdim);
  long lo = 0, hi = N;
  while (lo < hi) {
    const long mid = (lo + hi) / 2;
    if (key_less(&items.keys[mid * kdim], k, kdim))
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < N && std::equal(k, k + kdim, &items.keys[lo * kdim]) ? lo : -1;
}

void face_key(const double *a, const double *b, const double *c, double key[3]) {
  const double *p[3] = {a, b, c};
  std::sort(p, p + 3, [](const double *x, const double *y) { return key_less(x, y, 3); });
  for (int d = 0; d < 3; ++d)
    key[d] = (p[0][d] + p[1][d] + p[2][d]) / 3;
}

long scatter_by_key(MPI_Comm comm, const KeyedItems &all, const std::vector<double> &keys,
                    std::vector<double> &values, int kdim, int vdim) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  long N = rank == 0 ? (long)all.size(kdim) : 0;
  MPI_Bcast(&N, 1, MPI_LONG, 0, comm);
  std::vector<double> K(N * kdim), V(N * vdim);
  if (rank == 0) {
    K = all.keys;
    V = all.values;
  }
  MPI_Bcast(K.data(), (int)K.size(), MPI_DOUBLE, 0, comm);
  MPI_Bcast(V.data(), (int)V.size(), MPI_DOUBLE, 0, comm);
  const size_t n = keys.size() / kdim;
  values.assign(n * vdim, 0.0);
  long missing = 0;
  for (size_t i = 0; i < n; ++i) {
    const double *k = &keys[i * kdim];
    long lo = 0, hi = N; // first item not less than k
    while (lo < hi) {
      const long mid = (lo + hi) / 2;
      if (key_less(&K[mid * kdim], k, kdim))
        lo = mid + 1;
      else
        hi = mid;
    }
    if (lo < N && std::equal(k, k + kdim, &K[lo * kdim]))
      std::copy_n(&V[lo * vdim], vdim, &values[i * vdim]);
    else
      ++missing;
  }
  long total;
  MPI_Allreduce(&missing, &total, 1, MPI_LONG, MPI_SUM, comm);
  return total;
}

} // namespace fsi
