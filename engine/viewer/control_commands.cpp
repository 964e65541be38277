#include "viewer/control_commands.h"
#include "passes/shadows/techniques/techniques.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace avsm::viewer {

namespace {

float parse_number(const std::string& text, const std::string& what) {
  try {
    size_t used = 0;
    const float value = std::stof(text, &used);
    if (used == text.size()) return value;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument(what + " expects a number, got '" + text + "'");
}

int parse_whole(const std::string& text, const std::string& what) {
  const float value = parse_number(text, what);
  if (value != float(int(value)) || value < 0) throw std::invalid_argument(what + " expects a whole number, got '" + text + "'");
  return int(value);
}

// A whole number in [low, high]: the scene file's range for the field, so a bad value is
// refused here, with the range, rather than later by the renderer.
int parse_whole_in(const std::string& text, const std::string& what, int low, int high) {
  const int value = parse_whole(text, what);
  if (value < low || value > high)
    throw std::invalid_argument(what + " expects " + std::to_string(low) + " to " + std::to_string(high) + ", got '" +
                                text + "'");
  return value;
}

// "X,Y,Z": three finite numbers.
glm::vec3 parse_vec3(const std::string& text, const std::string& what) {
  const size_t first = text.find(','), second = text.find(',', first + 1);
  if (first == std::string::npos || second == std::string::npos || text.find(',', second + 1) != std::string::npos)
    throw std::invalid_argument(what + " expects X,Y,Z, got '" + text + "'");
  const glm::vec3 v{parse_number(text.substr(0, first), what),
                    parse_number(text.substr(first + 1, second - first - 1), what), parse_number(text.substr(second + 1), what)};
  if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) throw std::invalid_argument(what + " expects finite numbers, got '" + text + "'");
  return v;
}

// One of a setting's names, read by the scene file's own parser (`from_string`); `names`
// lists them in the message, when given.
template <typename T>
T parse_name(const std::string& text, std::optional<T> (*from_string)(std::string_view), const std::string& what,
             const char* kind, const char* names = nullptr) {
  if (const std::optional<T> value = from_string(text)) return *value;
  throw std::invalid_argument(what + ": unknown " + kind + " '" + text + "'" + (names ? std::string(" (") + names + ")" : ""));
}

bool parse_on_off(const std::string& text, const std::string& what) {
  if (text == "on") return true;
  if (text == "off") return false;
  throw std::invalid_argument(what + " expects on or off, got '" + text + "'");
}

}  // namespace

ControlCommand parse_control_command(const std::string& line) {
  std::istringstream words(line);
  std::string name, rest;
  words >> name;
  ControlCommand command;
  auto argument = [&](const char* what) {
    std::string word;
    if (!(words >> word)) throw std::invalid_argument("'" + name + "' needs " + what);
    return word;
  };
  if (name == "frame") {
    command.kind = ControlCommand::Kind::frame;
  } else if (name == "inspect") {
    command.kind = ControlCommand::Kind::inspect;
    const std::string xy = argument("X,Y");
    const size_t comma = xy.find(',');
    if (comma == std::string::npos) throw std::invalid_argument("'inspect' expects X,Y, got '" + xy + "'");
    command.pixel = {parse_number(xy.substr(0, comma), "inspect"), parse_number(xy.substr(comma + 1), "inspect")};
  } else if (name == "screenshot") {
    command.kind = ControlCommand::Kind::screenshot;
    command.directory = argument("a folder");
  } else if (name == "light") {
    command.kind = ControlCommand::Kind::light;
    command.light = uint32_t(parse_whole(argument("a light index"), "light"));
    command.field = argument("a field");
    command.value = argument("a value");
  } else if (name == "exposure") {
    command.kind = ControlCommand::Kind::exposure;
    command.exposure = parse_number(argument("a number"), "exposure");
  } else if (name == "orbit") {
    command.kind = ControlCommand::Kind::orbit;
    command.degrees = parse_number(argument("degrees"), "orbit");
    if (!(std::abs(command.degrees) <= 360.0f)) throw std::invalid_argument("'orbit' expects -360 to 360 degrees");
  } else if (name == "levels") {
    command.kind = ControlCommand::Kind::levels;
    const std::string light = argument("a light index or off");
    if (light != "off") command.overlay_light = uint32_t(parse_whole(light, "levels"));
  } else if (name == "time") {
    command.kind = ControlCommand::Kind::time;
    command.seconds = parse_number(argument("seconds"), "time");
  } else if (name == "play" || name == "pause") {
    command.kind = ControlCommand::Kind::time;
    command.play = name == "play";
  } else if (name == "quit") {
    command.kind = ControlCommand::Kind::quit;
  } else {
    throw std::invalid_argument("unknown command '" + name +
                                "' (frame, inspect X,Y, screenshot DIR, light I FIELD VALUE, exposure V, orbit DEGREES, levels I|off, time SECONDS, play, pause, quit)");
  }
  if (words >> rest) throw std::invalid_argument("'" + name + "': unexpected '" + rest + "'");
  return command;
}

void set_light_field(SceneOverrides& overrides, uint32_t light, const std::string& field, const std::string& value) {
  LightOverride& o = overrides.light(light);
  const std::string what = "light " + field;
  if (field == "technique") {
    if (!passes::find_shadow_technique(value))
      throw std::invalid_argument(what + ": unknown technique '" + value + "' (" + passes::shadow_technique_names() + ")");
    o.technique = value;
  } else if (field == "filter") {
    o.filter = parse_name(value, scene::shadow_filter_from_string, what, "filter");
  } else if (field == "nodes") {
    o.nodes = parse_whole(value, what);
  } else if (field == "resolution") {
    o.resolution = parse_whole(value, what);
  } else if (field == "sort") {
    o.sort = parse_on_off(value, what);
  } else if (field == "build") {
    o.build = parse_name(value, scene::shadow_build_from_string, what, "build", "lists, fixed");
  } else if (field == "fit") {
    o.fit = parse_name(value, scene::shadow_fit_from_string, what, "fit", "view, scene");
  } else if (field == "layout") {
    o.layout = parse_name(value, scene::shadow_layout_from_string, what, "layout", "dense, paged");
  } else if (field == "kernel") {
    o.kernel = parse_name(value, scene::shadow_kernel_from_string, what, "kernel", "none, box, gaussian");
  } else if (field == "cascades") {
    o.cascades = parse_whole_in(value, what, 1, 4);
  } else if (field == "clusters") {
    o.clusters = parse_whole_in(value, what, 0, 8);
  } else if (field == "on") {
    o.enabled = parse_on_off(value, what);
  } else if (field == "position") {
    o.position = parse_vec3(value, what);
  } else if (field == "direction") {
    const glm::vec3 direction = parse_vec3(value, what);
    if (!(glm::length(direction) > 0.0f)) throw std::invalid_argument(what + ": a direction needs a length, got '" + value + "'");
    o.direction = direction;
  } else {
    throw std::invalid_argument("unknown light field '" + field + "' (technique, nodes, resolution, filter, sort, build, fit, layout, kernel, cascades, clusters, on, position, direction)");
  }
}

}  // namespace avsm::viewer
