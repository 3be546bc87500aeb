// Serial HDF5 files written and read by one rank (rank 0) through the HDF5 C API, and the
// partition-independent exchange that feeds them: items (dofs, faces) carry a key made of
// reference coordinates, rank 0 stores them sorted by key, and a reader on any number of ranks
// finds its items by key.  Used by checkpoints (exact restart on another rank count) and by the
// wall-shear surface files.
#pragma once
#include "fsi/common.hpp"
#include <string>
#include <vector>

namespace fsi {

class H5File {
public:
  enum Mode { create, open_read };
  // Throws InputError if a file to read cannot be opened, OutputError if one cannot be created.
  H5File(const std::string &path, Mode mode);
  ~H5File();
  H5File(const H5File &) = delete;
  H5File &operator=(const H5File &) = delete;
  // Datasets of doubles (rows x cols) or ints; intermediate groups are created as needed.
  void write(const std::string &name, const std::vector<double> &v, size_t cols = 1);
  void write_ints(const std::string &name, const std::vector<long> &v, size_t cols = 1);
  bool has(const std::string &name) const;
  std::vector<double> read(const std::string &name) const; // InputError if missing
  // Scalar attributes on the root group.
  void set(const std::string &attr, double v);
  void set(const std::string &attr, const std::string &v);
  double get(const std::string &attr) const;
  bool has_attribute(const std::string &attr) const;
  std::string get_string(const std::string &attr) const;
  void flush();
  // Closes a file being written and reports a failure (OutputError); the destructor cannot.
  void close();

private:
  void make_groups(const std::string &name);
  long id_ = -1;
  std::string path_;
};

// Items with keys of `kdim` doubles and values of `vdim` doubles, `n` local items.  On rank 0
// returns all items sorted by key (keys then values, concatenated per item); empty elsewhere.
struct KeyedItems {
  std::vector<double> keys, values;
  size_t size(size_t kdim) const { return keys.size() / kdim; }
};
KeyedItems gather_sorted(MPI_Comm comm, const std::vector<double> &keys,
                         const std::vector<double> &values, int kdim, int vdim);
// Inverse: rank 0 holds `all` (sorted by key, e.g. read from a file); every rank receives the
// values of its local keys.  Returns the number of local keys not found (0 when the data belong
// to this mesh), summed over ranks.
long scatter_by_key(MPI_Comm comm, const KeyedItems &all, const std::vector<double> &keys,
                    std::vector<double> &values, int kdim, int vdim);
// Sort items by key in place (the order gather_sorted() leaves and scatter_by_key() expects).
void sort_items(KeyedItems &items, int kdim, int vdim);
// Index of the item with exactly this key in sorted items, or -1.
long find_key(const KeyedItems &items, const double *key, int kdim);
// The key of a triangle: its centroid summed in a canonical (lexicographic) vertex order, so that
// it does not depend on how a mesh orders the face's vertices.
void face_key(const double *a, const double *b, const double *c, double key[3]);

} // namespace fsi
