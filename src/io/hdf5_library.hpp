#pragma once
// HDF5, loaded when an XDMF file is first written rather than linked: Debian's serial HDF5 brings
// some 30 libraries with it (curl, GnuTLS, Kerberos, LDAP, ...), and loading them at start added
// about 7 MB to the resident memory of every run, --xdmf or not. The functions the XDMF writer
// calls, looked up in the library the build was configured with (its soname,
// CURVEMESH_HDF5_SONAME); hdf5.h gives their types, so a call is checked as a linked one would be.
#include <hdf5.h>

namespace curvemesh::io {

class Hdf5Library {
 public:
  // Loads and initialises the library; it stays loaded for the process (HDF5 closes itself at
  // exit). Throws std::runtime_error, with the loader's message, when it cannot be loaded or is
  // not the version whose headers the build used.
  Hdf5Library();
  ~Hdf5Library();
  Hdf5Library(const Hdf5Library&) = delete;
  Hdf5Library& operator=(const Hdf5Library&) = delete;

  // The functions, named as HDF5 names them without "H5".
  decltype(&H5Pcreate) Pcreate;
  decltype(&H5Pclose) Pclose;
  decltype(&H5Pset_fapl_core) Pset_fapl_core;
  decltype(&H5Pset_obj_track_times) Pset_obj_track_times;
  decltype(&H5Fcreate) Fcreate;
  decltype(&H5Fflush) Fflush;
  decltype(&H5Fget_file_image) Fget_file_image;
  decltype(&H5Fclose) Fclose;
  decltype(&H5Gcreate2) Gcreate2;
  decltype(&H5Gclose) Gclose;
  decltype(&H5Screate_simple) Screate_simple;
  decltype(&H5Sclose) Sclose;
  decltype(&H5Dcreate2) Dcreate2;
  decltype(&H5Dwrite) Dwrite;
  decltype(&H5Dclose) Dclose;
  // What hdf5.h's macros of the same names read once the library is open.
  hid_t P_FILE_ACCESS, P_GROUP_CREATE, P_DATASET_CREATE, T_NATIVE_DOUBLE, T_NATIVE_INT64;
  // H5F_ACC_TRUNC's value (the macro calls the library's H5check and H5open first).
  static constexpr unsigned F_ACC_TRUNC = 0x0002u;

 private:
  void* handle_;
};

}  // namespace curvemesh::io
