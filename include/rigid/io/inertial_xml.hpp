#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rigid/mass/mass_properties.hpp"

/// <inertial> elements of URDF, MJCF and SDF files: writers and readers that agree on the
/// conventions (docs/mass.md has the details).
///
///  - URDF `<inertial><origin xyz rpy/><mass value/><inertia ixx ixy ixz iyy iyz izz/>`:
///    the inertia is about the COM, expressed in the frame rotated by rpy (fixed-axis
///    roll-pitch-yaw: R = Rz(yaw) Ry(pitch) Rx(roll)); ixy, ixz, iyz are the tensor's
///    off-diagonal elements (−∫ρ x y dV), not the products of inertia.
///  - MJCF `<inertial pos mass fullinertia="xx yy zz xy xz yz"/>` (tensor elements in the body
///    frame) or `<inertial pos quat="w x y z" mass diaginertia="a b c"/>` (principal moments in
///    the frame rotated by quat).
///  - SDF `<inertial><pose>x y z roll pitch yaw</pose><mass/><inertia><ixx/>…</inertia>`:
///    pose of the inertial frame in the link frame (same rpy convention as URDF); the inertia
///    is about the COM in that frame; unset SDF elements take SDF's defaults (mass 1,
///    ixx = iyy = izz = 1, off-diagonals 0).
namespace rigid::io {

enum class InertialFormat { urdf, mjcf, sdf };

/// "urdf", "mjcf" or "sdf".
[[nodiscard]] const char* to_string(InertialFormat format);

/// Options of write_inertial_document.
struct InertialWriteOptions {
  /// Link (URDF/SDF) or body (MJCF) name.
  std::string name = "body";
  /// false: the inertia tensor in the link frame (URDF rpy = 0, MJCF fullinertia, SDF pose
  /// rotation 0). true: principal moments with the principal frame's rotation (URDF/SDF
  /// rpy, MJCF diaginertia + quat).
  bool principal = false;
};

/// A minimal complete document (robot/link, mujoco/worldbody/body, sdf/model/link) holding
/// one inertial with the mass properties `mp` (expressed in the link/body frame), with
/// shortest round-trip doubles.
/// @param inertial_frame with options.principal: the rotation R_LI of the inertial frame to
///   write (columns: its axes in the link frame) instead of mp.principal_axes(), e.g. a placed
///   primitive's own frame, which is a principal frame of every catalogue shape but the
///   tetrahedron. The tensor is re-expressed in it (R_LIᵀ I R_LI) and written as its diagonal.
/// @throws rigid::Error for a bad name, if inertial_frame is not a rotation within 1e-9, or if
///   the re-expressed tensor has an off-diagonal element above
///   MassProperties::kRelativeTolerance · tr I.
[[nodiscard]] std::string write_inertial_document(
    const MassProperties& mp, InertialFormat format, const InertialWriteOptions& options = {},
    const std::optional<Eigen::Matrix3d>& inertial_frame = std::nullopt);

/// One <inertial> read from a file.
struct InertialEntry {
  std::string name;  ///< link or body name ("" if the element has none)
  /// The file that holds the <inertial> element: the document read, or an MJCF file it
  /// <include>s.
  std::string file;
  int line = 0;      ///< line of the <inertial> element, in `file`
  double mass = 0;   ///< kg
  Eigen::Vector3d com = Eigen::Vector3d::Zero();        ///< COM in the link/body frame (m)
  Eigen::Matrix3d inertia_com = Eigen::Matrix3d::Zero();  ///< about the COM, link/body frame
  /// Why this inertial is unusable or not physical (a parse problem of one attribute, or
  /// MassProperties::check's report), or nullopt when it is valid.
  std::optional<std::string> problem;
  /// The validated mass properties (throws rigid::Error with `problem` if there is one).
  [[nodiscard]] MassProperties mass_properties() const;
};

/// Every inertial in an XML document, in document order; the format is detected from the
/// root element (robot → URDF, mujoco → MJCF, sdf → SDF). The inertial's own rotation
/// (URDF origin rpy, MJCF quat, SDF pose rpy) is applied, so entries are in the link frame.
/// MJCF <include file="..."> elements are followed as MuJoCo follows them (the path is
/// relative to the folder of `source`; the included file's elements take the include's
/// place), and their inertials carry their own file and line.
/// @param source file name used in messages.
/// @throws rigid::Error "source:line: ..." for malformed XML or an unknown root element;
///   "file:line: ..." for an <include> that cannot be read or parsed (naming the file).
[[nodiscard]] std::vector<InertialEntry> read_inertials(const std::string& xml,
                                                        const std::string& source);

/// read_inertials on the contents of a file. @throws rigid::Error if it does not exist, is not
/// a regular file (a directory, FIFO or device: refused before it is opened) or cannot be read.
[[nodiscard]] std::vector<InertialEntry> read_inertials_file(const std::string& path);

/// Detected format of a document (as read_inertials does). @throws like read_inertials.
[[nodiscard]] InertialFormat detect_inertial_format(const std::string& xml,
                                                    const std::string& source);

/// Fixed-axis roll-pitch-yaw (rad) of URDF/SDF to a rotation: R = Rz(y) Ry(p) Rx(r).
[[nodiscard]] Eigen::Matrix3d rotation_from_rpy(const Eigen::Vector3d& rpy);
/// The inverse of rotation_from_rpy, pitch in [−π/2, π/2].
[[nodiscard]] Eigen::Vector3d rpy_from_rotation(const Eigen::Matrix3d& R);

}  // namespace rigid::io
