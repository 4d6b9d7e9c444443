#include "cli/mat_file.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <unistd.h>

#ifdef MBGEN_HAVE_MATIO
#include <matio.h>
#endif

namespace mbgen::cli {

void MatFile::matrix(const std::string& name, const Eigen::MatrixXd& m) {
  Variable v{Kind::Real, name, {static_cast<std::size_t>(m.rows()), static_cast<std::size_t>(m.cols())}, {}, {}, {}};
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i) v.re.push_back(m(i, j) == 0 ? 0.0 : m(i, j));  // no -0, as the JSON
  variables_.push_back(std::move(v));
}

void MatFile::complex_array(const std::string& name, const std::vector<std::size_t>& dims,
                            const std::vector<std::complex<double>>& values) {
  Variable v{Kind::Complex, name, dims, {}, {}, {}};
  for (const std::complex<double>& z : values) {
    v.re.push_back(z.real() == 0 ? 0.0 : z.real());
    v.im.push_back(z.imag() == 0 ? 0.0 : z.imag());
  }
  variables_.push_back(std::move(v));
}

void MatFile::text(const std::string& name, const std::string& value) {
  variables_.push_back({Kind::Text, name, {1, value.size()}, {}, {}, {value}});
}

void MatFile::texts(const std::string& name, const std::vector<std::string>& values) {
  variables_.push_back({Kind::Texts, name, {values.size(), 1}, {}, {}, values});
}

#ifdef MBGEN_HAVE_MATIO

bool mat_file_available() { return true; }

namespace {

// A char row; the caller frees it (its data is the string's, not copied).
matvar_t* char_row(const char* name, const std::string& s) {
  std::size_t dims[2] = {1, s.size()};
  return Mat_VarCreate(name, MAT_C_CHAR, MAT_T_UTF8, 2, dims, const_cast<char*>(s.data()), MAT_F_DONT_COPY_DATA);
}

// Frees a variable whose data this file owns (created with MAT_F_DONT_COPY_DATA): matio must not free it.
void release(matvar_t* var) {
  if (!var) return;
  var->data = nullptr;
  Mat_VarFree(var);
}

}  // namespace

std::string MatFile::bytes(const std::string& header) const {
  if (header.size() > 116) throw std::invalid_argument("MatFile: the header text holds 116 characters");
  // libmatio writes to a file: a private temporary one, read back and removed (the caller commits the bytes).
  std::string path = (std::filesystem::temp_directory_path() / "mbgen-mat-XXXXXX").string();
  const int fd = mkstemp(path.data());
  if (fd < 0) throw std::runtime_error("cannot create a temporary file for the .mat output");
  close(fd);
  struct Remove {
    std::string path;
    ~Remove() { std::remove(path.c_str()); }
  } remove{path};
  mat_t* mat = Mat_CreateVer(path.c_str(), header.c_str(), MAT_FT_MAT5);
  if (!mat) throw std::runtime_error("libmatio cannot create the .mat file");
  for (const Variable& v : variables_) {
    std::vector<std::size_t> dims = v.dims;
    matvar_t* var = nullptr;
    std::vector<matvar_t*> cells;
    mat_complex_split_t split{const_cast<double*>(v.re.data()), const_cast<double*>(v.im.data())};
    switch (v.kind) {
      case Kind::Real:
        var = Mat_VarCreate(v.name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, static_cast<int>(dims.size()), dims.data(),
                            const_cast<double*>(v.re.data()), MAT_F_DONT_COPY_DATA);
        break;
      case Kind::Complex:
        var = Mat_VarCreate(v.name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, static_cast<int>(dims.size()), dims.data(),
                            &split, MAT_F_DONT_COPY_DATA | MAT_F_COMPLEX);
        break;
      case Kind::Text: var = char_row(v.name.c_str(), v.strings[0]); break;
      case Kind::Texts:
        for (const std::string& s : v.strings) cells.push_back(char_row(nullptr, s));
        var = Mat_VarCreate(v.name.c_str(), MAT_C_CELL, MAT_T_CELL, 2, dims.data(), cells.data(),
                            MAT_F_DONT_COPY_DATA);
        break;
    }
    const int failed = var ? Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE) : 1;
    for (matvar_t* cell : cells) release(cell);
    release(var);
    if (failed) {
      Mat_Close(mat);
      throw std::runtime_error("libmatio could not write the variable `" + v.name + "`");
    }
  }
  Mat_Close(mat);
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

#else

bool mat_file_available() { return false; }

std::string MatFile::bytes(const std::string&) const {
  throw std::runtime_error("this mbgen was built without libmatio: .mat files cannot be written");
}

#endif

}  // namespace mbgen::cli
