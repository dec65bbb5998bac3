#pragma once
// Errors thrown by tumble. Every message says what is wrong, where (file:line:column, triangle or
// edge index, body name, time step) and how to fix it; the CLI prints it as one line.
#include <stdexcept>
#include <string>

namespace tumble {

/// Base of every exception tumble throws.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A number or argument given by the user is out of its domain (negative mass, zero size, NaN...).
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

/// Mass properties that no physical body can have (not positive definite, triangle inequality...).
class InvalidMassProperties : public Error {
 public:
  using Error::Error;
};

/// A triangle mesh that cannot bound a solid (open, non-manifold, inconsistent winding, degenerate).
class MeshError : public Error {
 public:
  using Error::Error;
};

/// A mesh that bounds no solid because it is a sheet — open (holes) or enclosing no volume — so that
/// shell mass properties would apply. Callers add how to ask for them where they are (a command-line
/// flag, a scene key).
class NotASolidError : public MeshError {
 public:
  using MeshError::MeshError;
};

/// A file that cannot be read or parsed.
class FileError : public Error {
 public:
  using Error::Error;
};

}  // namespace tumble
