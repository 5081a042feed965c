#include "io/hdf5_library.hpp"

#include <dlfcn.h>

#include <stdexcept>
#include <string>

namespace curvemesh::io {

namespace {

const char* loader_error() {
  const char* e = dlerror();
  return e ? e : "unknown error";
}

// The symbol `name` of `handle` as a T (a function pointer, or a pointer to a variable).
template <class T>
T symbol(void* handle, const char* name) {
  void* p = dlsym(handle, name);
  if (!p) throw std::runtime_error(std::string("HDF5 (" CURVEMESH_HDF5_SONAME ") has no ") + name + ": " + loader_error());
  return reinterpret_cast<T>(p);
}

}  // namespace

Hdf5Library::Hdf5Library() {
  // RTLD_NODELETE: HDF5 registers an exit handler that must find it loaded.
  handle_ = dlopen(CURVEMESH_HDF5_SONAME, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
  if (!handle_) throw std::runtime_error(std::string("cannot load HDF5 (" CURVEMESH_HDF5_SONAME "): ") + loader_error());
  try {
    if (symbol<decltype(&H5open)>(handle_, "H5open")() < 0) throw std::runtime_error("HDF5: cannot initialise");
    unsigned major = 0, minor = 0, release = 0;
    symbol<decltype(&H5get_libversion)>(handle_, "H5get_libversion")(&major, &minor, &release);
    if (major != H5_VERS_MAJOR || minor != H5_VERS_MINOR)
      throw std::runtime_error("HDF5 (" CURVEMESH_HDF5_SONAME ") is version " + std::to_string(major) + "." +
                               std::to_string(minor) + ", not the " H5_VERSION " the program was built with");
    Pcreate = symbol<decltype(Pcreate)>(handle_, "H5Pcreate");
    Pclose = symbol<decltype(Pclose)>(handle_, "H5Pclose");
    Pset_fapl_core = symbol<decltype(Pset_fapl_core)>(handle_, "H5Pset_fapl_core");
    Pset_obj_track_times = symbol<decltype(Pset_obj_track_times)>(handle_, "H5Pset_obj_track_times");
    Fcreate = symbol<decltype(Fcreate)>(handle_, "H5Fcreate");
    Fflush = symbol<decltype(Fflush)>(handle_, "H5Fflush");
    Fget_file_image = symbol<decltype(Fget_file_image)>(handle_, "H5Fget_file_image");
    Fclose = symbol<decltype(Fclose)>(handle_, "H5Fclose");
    Gcreate2 = symbol<decltype(Gcreate2)>(handle_, "H5Gcreate2");
    Gclose = symbol<decltype(Gclose)>(handle_, "H5Gclose");
    Screate_simple = symbol<decltype(Screate_simple)>(handle_, "H5Screate_simple");
    Sclose = symbol<decltype(Sclose)>(handle_, "H5Sclose");
    Dcreate2 = symbol<decltype(Dcreate2)>(handle_, "H5Dcreate2");
    Dwrite = symbol<decltype(Dwrite)>(handle_, "H5Dwrite");
    Dclose = symbol<decltype(Dclose)>(handle_, "H5Dclose");
    // The identifiers behind H5P_FILE_ACCESS, ..., set by H5open.
    P_FILE_ACCESS = *symbol<const hid_t*>(handle_, "H5P_CLS_FILE_ACCESS_ID_g");
    P_GROUP_CREATE = *symbol<const hid_t*>(handle_, "H5P_CLS_GROUP_CREATE_ID_g");
    P_DATASET_CREATE = *symbol<const hid_t*>(handle_, "H5P_CLS_DATASET_CREATE_ID_g");
    T_NATIVE_DOUBLE = *symbol<const hid_t*>(handle_, "H5T_NATIVE_DOUBLE_g");
    T_NATIVE_INT64 = *symbol<const hid_t*>(handle_, "H5T_NATIVE_INT64_g");
  } catch (...) {
    dlclose(handle_);
    throw;
  }
}

Hdf5Library::~Hdf5Library() {
  dlclose(handle_);
}

}  // namespace curvemesh::io
