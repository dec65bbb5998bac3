// URDF (http://wiki.ros.org/urdf/XML): <robot> of <link>s, each with an optional <inertial> and any
// number of <collision> and <visual> geometries, and <joint>s between them. Lengths in metres, angles
// in radians; rpy is roll, pitch, yaw about fixed x, y, z (R = Rz Ry Rx).
#include <cstring>

#include <fmt/format.h>

#include "readers.hpp"

namespace tumble::robot {

namespace {

/// An <origin xyz rpy> (both default to zero), or the identity when there is none.
Pose origin_of(const XmlSource& xml, const pugi::xml_node& parent) {
  const pugi::xml_node origin = parent.child("origin");
  if (!origin) return {};
  const std::vector<double> xyz = xml.numbers(origin, "xyz", 3, {0, 0, 0});
  const std::vector<double> rpy = xml.numbers(origin, "rpy", 3, {0, 0, 0});
  return {rotation_rpy(Vec3(rpy[0], rpy[1], rpy[2])), Vec3(xyz[0], xyz[1], xyz[2])};
}

/// A <collision> or <visual> element's geometry; false (and a line in `skipped`) for none.
bool read_geometry(const XmlSource& xml, const pugi::xml_node& element, Geometry& g,
                   std::vector<std::string>& skipped) {
  g.name = element.attribute("name").value();
  g.element = element.name();
  g.line = xml.line_of(element);
  g.pose = origin_of(xml, element);
  const pugi::xml_node geometry = element.child("geometry");
  const pugi::xml_node shape = geometry.first_child();
  if (!geometry || !shape) {
    skipped.push_back(fmt::format("<{}> at line {} has no <geometry>", g.element, g.line));
    return false;
  }
  const std::string kind = shape.name();
  if (kind == "box") {
    const std::vector<double> s = xml.numbers(shape, "size", 3);
    g.shape = Box{Vec3(s[0], s[1], s[2])};
  } else if (kind == "sphere") {
    g.shape = Sphere{xml.number(shape, "radius")};
  } else if (kind == "cylinder") {
    g.shape = Cylinder{xml.number(shape, "radius"), xml.number(shape, "length")};
  } else if (kind == "capsule") {  // not in the URDF spec, but read by several tools
    g.shape = Capsule{xml.number(shape, "radius"), xml.number(shape, "length")};
  } else if (kind == "mesh") {
    g.mesh_uri = shape.attribute("filename").value();
    if (g.mesh_uri.empty()) xml.fail(shape, "needs filename=\"...\" (the mesh file)");
    const std::vector<double> s = xml.numbers(shape, "scale", 3, {1, 1, 1});
    g.scale = Vec3(s[0], s[1], s[2]);
  } else {
    skipped.push_back(
        fmt::format("<{}> at line {}: a <{}> geometry is not one tumble knows", g.element, g.line, kind));
    return false;
  }
  return true;
}

Inertial read_inertial(const XmlSource& xml, const pugi::xml_node& element) {
  Inertial in;
  in.span = xml.span_of(element);
  in.frame = origin_of(xml, element);
  const pugi::xml_node origin = element.child("origin");
  in.rotated = origin && origin.attribute("rpy") && !in.frame.R.isIdentity(0.0);
  const pugi::xml_node mass = element.child("mass");
  if (!mass) xml.fail(element, "needs <mass value=\"...\"/>");
  in.mass = xml.number(mass, "value");
  in.mass_text = mass.attribute("value").value();
  const pugi::xml_node I = element.child("inertia");
  if (!I)
    xml.fail(element,
             "needs <inertia ixx=\"...\" ixy=\"...\" ixz=\"...\" iyy=\"...\" iyz=\"...\" izz=\"...\"/>");
  const double ixx = xml.number(I, "ixx"), iyy = xml.number(I, "iyy"), izz = xml.number(I, "izz");
  // The products default to 0 (urdfdom reads them so); the moments are required.
  const double ixy = xml.number(I, "ixy", 0.0), ixz = xml.number(I, "ixz", 0.0),
               iyz = xml.number(I, "iyz", 0.0);
  in.inertia_written << ixx, ixy, ixz, ixy, iyy, iyz, ixz, iyz, izz;
  return in;
}

}  // namespace

void read_urdf(const XmlSource& xml, const pugi::xml_node& robot, RobotModel& model) {
  model.name = robot.attribute("name").value();
  for (const pugi::xml_node& element : robot.children("link")) {
    Link& link = model.links.emplace_back();
    link.name = element.attribute("name").value();
    if (link.name.empty()) xml.fail(element, "needs name=\"...\"");
    link.line = xml.line_of(element);
    if (const pugi::xml_node inertial = element.child("inertial"))
      link.inertial = read_inertial(xml, inertial);
    for (const char* kind : {"collision", "visual"}) {
      std::vector<Geometry>& list = std::strcmp(kind, "collision") == 0 ? link.collision : link.visual;
      for (const pugi::xml_node& g : element.children(kind)) {
        Geometry geometry;
        if (read_geometry(xml, g, geometry, link.skipped)) list.push_back(std::move(geometry));
      }
    }
  }
  for (const pugi::xml_node& element : robot.children("joint")) {
    Joint& joint = model.joints.emplace_back();
    joint.name = element.attribute("name").value();
    joint.type = element.attribute("type").value();
    joint.parent = element.child("parent").attribute("link").value();
    joint.child = element.child("child").attribute("link").value();
    if (joint.parent.empty() || joint.child.empty()) {
      xml.fail(element, "needs <parent link=\"...\"/> and <child link=\"...\"/>");
    }
    joint.origin = origin_of(xml, element);
    joint.line = xml.line_of(element);
  }
}

}  // namespace tumble::robot
