// Typed exceptions for bad data and bad requests. Programmer mistakes use assert instead.
#pragma once
#include <stdexcept>
#include <string>

namespace tsp {

/// Base of every error thrown for bad input; what() names the file, the field and the problem.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The file system failed: a file is missing, unreadable, unwritable, or the disk is full.
class IoError : public Error {
 public:
  using Error::Error;
};

/// A file was read but does not hold what was expected (rank, type, field, version, corruption).
class FormatError : public Error {
 public:
  using Error::Error;
};

/// The user asked for something invalid or inconsistent (an option's value, a missing argument).
class UsageError : public Error {
 public:
  using Error::Error;
};

}  // namespace tsp
