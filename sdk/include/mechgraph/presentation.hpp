#pragma once
// What a host needs to present a port, declared by the node type and never guessed from names
// (docs/design/sdk-1.0.md, section 1.6; issue 30, item 2): the figure a table or series calls for
// (its role), labels and units of its channels, which angle an angle counts (an angle frame, with
// where its zero is and how it maps onto another frame), named codes of an enumeration channel,
// points another port puts on the figure, and the notes a node makes when a parameter is given.
// Hosts draw, label and convert from these declarations only; a port without one is drawn plainly.
//
// Every struct maps field for field onto the plain-C declarations of section 1.6 (c/present.h):
// Role -> MG_ROLE_*, ChannelFlag -> MG_CH_*, Code -> mg_code, ChannelDecl -> mg_channel_decl,
// XyPair -> mg_xy_pair, PointMarks -> mg_point_marks, Presentation -> mg_presentation,
// AngleFrame -> mg_angle_frame, NoteDecl -> mg_note_decl. One difference of spelling: the C++
// layer names a frame by its id ("cam"), where C counts it by its index in the node's frames; the
// exporter writes the index.
#include <mechgraph/dimension.hpp>

#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

namespace mechgraph {

/// The figure a table or series port calls for (MG_ROLE_*). Unknown roles are drawn as plain.
enum class Role : std::int32_t {
  plain = 0,               // each channel over the axis, compared across nodes
  derivative_family = 1,   // channels f, f', f'', ... over the axis: one stacked panel
  curve_over_channel = 2,  // channels drawn over `x_channel`, not over the axis
  drawing_to_scale = 3,    // x/y pairs, equal scales, DXF layers
  events = 4,              // few rows: printed as rows; code channels shown by name
  histogram = 5,
};

/// What a channel is besides a curve over the axis (MG_CH_*), or-ed together.
namespace channel_flag {
inline constexpr std::uint32_t alt_axis = 0x01u;        // another scale of the axis: not a curve
inline constexpr std::uint32_t curvature = 0x02u;       // a radius of curvature: drawn as 1/rho apart
inline constexpr std::uint32_t positive_only = 0x04u;   // drawn only where > 0
inline constexpr std::uint32_t not_drawn = 0x08u;       // in CSV and JSON, not in figures
inline constexpr std::uint32_t line_from_mark = 0x10u;  // a straight line from mark `from_mark` (at 0) to the row of the largest x
/// May jump where an events output of the same node (role events, its axis the same quantity and
/// frame as this table's) has a row: drawn in pieces between those axis values, never a line
/// across one (an impact's velocity, the cam force at a landing).
inline constexpr std::uint32_t jumps_at_events = 0x20u;
/// As a figure's x (curve_over_channel's x_channel): the range is the working range the rows
/// span; a mark beyond it by more than a quarter of that span is named at the plot's edge with its
/// value instead of stretching the axis, and a line from it is cut at the edge.
inline constexpr std::uint32_t range_of_rows = 0x40u;
}  // namespace channel_flag

/// One named value of an enumeration channel ("1 contact_lost"): shown by name wherever the
/// channel is shown (terminal, CSV name column, JSON `codes`, report tables, Python).
struct Code {
  double value = 0.0;
  std::string name;  // an identifier: "contact_lost"
  std::string doc;   // "the valve leaves the cam"
};

/// A channel (or a table's axis) as a reader meets it.
struct ChannelDecl {
  std::string name;            // the channel it declares
  Dimension dimension{};       // informative: the table's column carries the value's own
  std::string label;           // "opening after TDC"; empty: the name with '_' read as ' '
  std::string display_unit;    // "mm"; empty: the column's own
  std::string angle_frame;     // id of a frame of the node type; for d/dphi channels the angle they count
  int derivative_order = -1;   // derivative_family: 0 the value, 1, 2, 3 ...; -1 none
  std::uint32_t flags = 0;     // channel_flag::*
  std::vector<Code> codes;     // an enumeration channel's named values
  std::string from_mark;       // line_from_mark: the label of the table's mark the line starts at

  /// A declaration of channel `name` (of dimension `d`, informative), to be completed fluently:
  /// ChannelDecl::of("speed").derivative(1).in_frame("shaft").
  static ChannelDecl of(std::string name, Dimension d = {}) {
    ChannelDecl c;
    c.name = std::move(name);
    c.dimension = d;
    return c;
  }
  ChannelDecl& labelled(std::string text) { label = std::move(text); return *this; }
  ChannelDecl& in_frame(std::string frame) { angle_frame = std::move(frame); return *this; }
  ChannelDecl& derivative(int order) { derivative_order = order; return *this; }
  ChannelDecl& flag(std::uint32_t f) { flags |= f; return *this; }
  ChannelDecl& with_codes(std::vector<Code> c) { codes = std::move(c); return *this; }
  ChannelDecl& line_from(std::string mark) { flags |= channel_flag::line_from_mark; from_mark = std::move(mark); return *this; }
  /// The label a host shows: `label`, else the name with '_' read as ' '.
  std::string shown_label() const {
    if (!label.empty()) return label;
    std::string spoken = name;
    for (char& c : spoken)
      if (c == '_') c = ' ';
    return spoken;
  }
  /// The code's name for `value`, or "" when the value has none.
  std::string_view code_name(double value) const {
    for (const Code& c : codes)
      if (c.value == value) return c.name;
    return {};
  }
};

/// A drawing to scale: channels `x`, `y` trace a curve on layer `layer`.
struct XyPair {
  std::string x, y;       // channel names
  std::string layer;      // DXF layer (in capitals): "outline", "construction"
  std::string label;      // legend: "outline"; empty: the layer
  std::int32_t stroke = 0;  // 0 outline, 1 construction (dotted), 2 a part shown at rest
};

/// Points another output of the same node puts on this figure: row `row` of table port `port`,
/// x from each of `x_channels` (angles in their channel's frame), y from that row's axis value when
/// `y_from_axis`; each labelled. `caption` says what the points are; "{axis}" stands for that row's
/// axis value in the unit the figure shows it ("events at {axis} lift").
struct PointMarks {
  std::string port;
  std::size_t row = 0;
  std::vector<std::string> x_channels;
  std::vector<std::string> labels;
  bool y_from_axis = true;
  std::string caption;
};

/// The presentation of one table or series port.
struct Presentation {
  Role role = Role::plain;
  bool has_axis = false;       // whether `axis` is declared (C: a NULL pointer when not)
  ChannelDecl axis;
  std::vector<ChannelDecl> channels;  // the declared ones; others are plain
  std::string x_channel;              // curve_over_channel
  std::vector<XyPair> pairs;          // drawing_to_scale
  std::vector<PointMarks> points;
  std::string figure_title;           // "Force over travel": the host adds " of " and the nodes
  std::string caption;                // said under the figure

  Presentation& with_axis(ChannelDecl a) { axis = std::move(a); has_axis = true; return *this; }
  Presentation& with(ChannelDecl c) { channels.push_back(std::move(c)); return *this; }
  /// The declaration of channel `name`, or nullptr.
  const ChannelDecl* find(std::string_view name) const {
    if (has_axis && axis.name == name) return &axis;
    for (const ChannelDecl& c : channels)
      if (c.name == name) return &c;
    return nullptr;
  }
  bool empty() const { return role == Role::plain && !has_axis && channels.empty() && pairs.empty() && points.empty() && figure_title.empty() && caption.empty(); }
};

/// An angle reference of a node type. The host compares frames only by id and shows the label
/// and the tag; it knows no frame by name.
struct AngleFrame {
  std::string id;        // unique within the node type
  std::string label;     // an axis title: "shaft angle from the peak"
  std::string unit_tag;  // shown after degrees: "deg (shaft)", "mm/deg (shaft)"
  std::string zero;      // where zero is, in words (describe, JSON)
  /// Optional mapping from another frame of the node type: this = scale * base + offset_param
  /// (SI). A figure over the base frame is drawn in this one when every node drawn has
  /// `offset_param` given (an optional parameter), else in the base frame.
  std::string base_frame;
  double scale = 1.0;
  std::string offset_param;
  /// Optional periodic marks every `mark_spacing` (SI, 0: none), labelled in turn from 0; an angle
  /// is quoted from the nearest mark as |a - mark| + (before|after) + label: "3.4 ATDC".
  double mark_spacing = 0.0;
  std::vector<std::string> mark_labels;
  std::string before, after;
};

/// A note the node makes while it computes `output` when parameter `when_param` is given: a host
/// that shows notes wants that output of such a node.
struct NoteDecl {
  std::string output;
  std::string when_param;
  std::string doc;
};

}  // namespace mechgraph
