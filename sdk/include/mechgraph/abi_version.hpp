#pragma once
// The plugin ABI version. CMake reads the number from the #define below. What bumps it is written
// down in docs/writing-plugins.md ("When the ABI changes"): in short, any change to a class, struct,
// enum or inline function in sdk/include that a compiled plugin relies on (layout, virtual functions,
// members, the descriptor, the entry). Additions that a plugin cannot see (a new free function in
// libmechgraph, a new header) do not.
// 2: table values, effects with their outputs and parameters, ValveMotion and Spring interfaces,
//    CamLaw::higher_derivatives.
// 3: EvalContext::wanted (which outputs are read downstream).
// 4: the entry is a plain C function `mechgraph_plugin_entry` (no Boost.DLL alias); the descriptor
//    carries the SDK version; DomainObject::contract_problem (the host checks interface contracts);
//    ParamSpec::example_value; out-of-line destructors (key functions) for every shared interface.
// 7: CamLaw::monotone_breaks and CamLaw::lift_integrals (closed-form queries).
// 8: the Follower domain interface (mechgraph/domain/follower.hpp); cam.contour takes a follower.
// 9: NodeType::forecast (a node's work, memory and output size said before it runs).
// 10: presentation declarations (presentation.hpp): PortSpec::label, angle_frame, presentation;
//     NodeInfo::frames and notes.
//     ParamSpec::range_reason (why each finite bound of a parameter is where it is).
#define MECHGRAPH_PLUGIN_ABI_VERSION 10
