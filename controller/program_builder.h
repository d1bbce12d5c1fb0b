// Applies blocks of address words (letter + number) with the modal state of a Fanuc-style
// control and collects the resulting ProgramBlocks. Both part-program readers use it: the
// G-code parser (controller/gcode_parser.h) and the YAML `program:` list
// (bench/scenario/program_reader.h). Units at this boundary are the programmer's: coordinates,
// I/J/K and R in mm (inch under G20), F in mm/min (in/min), G4's P and X per dialect;
// the Program is SI.
//
// Words and modal groups (docs/gcode.md lists them per dialect; ProgramOptions::dialect,
// controller/gcode_dialect.h, selects one):
//   G0 G1 G2 G3   motion (modal). Power-up state: G1, so a block with coordinates only and
//                 no motion G ever programmed is a linear move (Fanuc parameter G01 = 1).
//   G4            dwell, one shot. fanuc: P in ms written without a decimal point (a
//                 decimal P is refused: linuxcnc and grbl read it in s), or X/U in s; no
//                 other motion word in the block. linuxcnc, grbl: P in s; the block's
//                 motion, if any, runs after the dwell (their order of execution).
//   G17 G18 G19   plane XY (power-up), ZX, YZ (modal); a change of the normal axis makes a
//                 helix.
//   G20 G21       inch (lengths and F scaled by 25.4) / mm (power-up), modal, any block.
//   G28 G30       return through the intermediate point (X Y Z, per G90/G91) to the
//                 reference position ProgramOptions::g28_mm/g30_mm (refused when unset), in
//                 two rapid moves; the axes with a word return (linuxcnc, grbl: all axes
//                 when there is none; fanuc: none).
//   G61 G61.1 G64 path mode (modal; grbl: G61 only; fanuc: G61, G64; linuxcnc: all, G64
//                 with P and Q). linuxcnc's G64 blends corners within P and merges
//                 collinear lines within Q (controller/corner_blend.h); every other mode
//                 follows the bench's corner rule (fanuc's G64 with one warning).
//   G90 G91       absolute (power-up) / incremental X Y Z (modal).
//   G90.1 G91.1   absolute / incremental (power-up) I J K (linuxcnc; grbl: G91.1).
//   F             feed, mm/min (in/min under G20), > 0 (modal; NaN until the first F).
//   X Y Z         end point, absolute or incremental per G90/G91.
//   I J K         arc centre: offsets from the start point (or the centre under G90.1);
//                 only the two of the active plane (G17: I J, G18: K I, G19: J K).
//   R             arc radius: R > 0 the arc of at most 180 degrees, R < 0 the longer one.
//   N             sequence number, ignored (accepted anywhere in the block).
// Every word at most once per block; at most one word of each G group.
//
// Decisions:
//   - A block without motion (only N, F or modal G words; G2/G3 without end point or
//     centre) produces no ProgramBlock; neither does a G0/G1 block whose end equals its
//     start.
//   - An arc needs I/J/K or R (not both). Its end and start coincide (within 1e-6 mm in the
//     plane; the end is then set to the start exactly) for a full circle, which only
//     I/J/K can describe. The start and end radii must agree within the dialect's arc
//     tolerance (ProgramOptions::ArcRule; fanuc: 1e-3 mm, the least input increment, or
//     1e-6 of the radius); the programmed end point is kept as written.
//   - R shorter than half the chord by more than that tolerance is an error; within it, the
//     centre is the chord's midpoint.
//   - Numbers are taken as written in mm or inch (decimal-point input with
//     "calculator-type" input: X10 is 10 mm).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "controller/gcode_dialect.h"
#include "controller/program.h"
#include "controller/program_words.h"

namespace shapebench::controller {

class BlockWords;  // controller/block_words.h

class ProgramBuilder {
 public:
  explicit ProgramBuilder(const Eigen::Vector3d& start_m = Eigen::Vector3d::Zero(),
                          ProgramOptions options = {});

  // Applies one block; throws ProgramError (the builder's state is then unspecified).
  void Apply(const Block& block);

  const Program& program() const { return program_; }
  Program TakeProgram() { return std::move(program_); }

  // The modal state after the blocks applied so far.
  const Eigen::Vector3d& position_m() const { return position_m_; }
  MotionKind motion() const { return motion_; }
  Plane plane() const { return plane_; }
  bool incremental() const { return incremental_; }
  double feed_m_s() const { return feed_m_s_; }
  double unit_m() const { return unit_m_; }  // 1e-3 (G21) or 25.4e-3 (G20)

 private:
  void AddRapid(const ProgramBlock& here, const Eigen::Vector3d& end_m);
  void ReferenceReturn(const BlockWords& words, const ProgramBlock& here);
  void NotePathMode(const BlockWords& words, int line);

  ProgramOptions options_;
  Program program_;
  Eigen::Vector3d position_m_;
  MotionKind motion_ = MotionKind::kLinear;
  Plane plane_ = Plane::kXY;
  bool incremental_ = false;
  double feed_m_s_ = NAN;
  double unit_m_ = 1e-3;
  bool absolute_centre_ = false;
  bool blending_warned_ = false;
  double blend_tolerance_m_ = -1.0;  // linuxcnc's G64 P (ProgramBlock::blend_tolerance_m)
  double merge_tolerance_m_ = 0.0;   // and Q
};


}  // namespace shapebench::controller
