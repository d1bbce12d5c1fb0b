// Optimised kernels for SUNDIALS' serial N_Vector.
//
// Debian 12's libsundials 6.4.1 is compiled without optimisation (its object code keeps
// every loop variable on the stack: `disassemble N_VWSqrSumLocal_Serial` in gdb shows it).
// On shapebench's 2- to 30-state plants a CVODE step is mostly calls to those vector
// kernels, so they cost more than the arithmetic. SUNDIALS lets a user supply a vector's
// operations (the N_Vector ops table; clones copy it), so shapebench keeps the serial
// vector's data layout and replaces the hot operations with the same arithmetic compiled
// with shapebench's flags. Each replacement gives the same bits as SUNDIALS' own kernel, in
// the same order of operations and with the same special cases (a linear sum with equal or
// opposite coefficients factors them out, as SUNDIALS does):
// tests/model/serial_vector_ops_test.cc compares them with N_V*_Serial bit for bit.
#pragma once

#include <nvector/nvector_serial.h>

namespace shapebench::model {

// Replaces the hot operations of a serial vector `v` (created by N_VNew_Serial, fused
// operations enabled or not) with shapebench's kernels. Vectors cloned from `v` afterwards
// (CVODE's own, from CVodeInit's y) get them too. Throws std::invalid_argument if `v` is
// not a serial vector.
void UseOptimizedSerialOps(N_Vector v);

}  // namespace shapebench::model
