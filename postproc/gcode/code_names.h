// The G and M codes the interpreter acts on, by name: the number as the
// tables of codes.h hold it (times ten: G61.1 is 611) and what it does, as
// LinuxCNC's enum GCodes names them (G_73 there). Plain ints, not an enum:
// a code read from a word is an int, stored and compared as one. Where a
// dialect gives a number another meaning, the name says whose it is; the
// group the code was found in tells them apart (G5 is a spline in the
// motion group, a Fanuc high-speed mode in its own).
#pragma once

namespace vcpost::gcode {

// Motion (group 1) and the canned cycles.
inline constexpr int G_0_rapid = 0;
inline constexpr int G_1_linear = 10;
inline constexpr int G_2_arc_cw = 20;
inline constexpr int G_3_arc_ccw = 30;
inline constexpr int G_5_cubic_spline = 50;
inline constexpr int G_5_1_quadratic_spline = 51;
inline constexpr int G_5_2_nurbs = 52;
inline constexpr int G_73_chip_break_drill = 730;
inline constexpr int G_74_left_hand_tap = 740;
inline constexpr int G_76_fine_bore = 760;  // Fanuc (RS274NGC's G76 is lathe threading)
inline constexpr int G_80_cycle_off = 800;
inline constexpr int G_81_drill = 810;
inline constexpr int G_82_drill_dwell = 820;
inline constexpr int G_83_peck_drill = 830;
inline constexpr int G_84_right_hand_tap = 840;
inline constexpr int G_85_bore_feed_out = 850;
inline constexpr int G_86_bore_spindle_stop = 860;
inline constexpr int G_87_back_bore = 870;
inline constexpr int G_88_bore_manual_out = 880;
inline constexpr int G_89_bore_dwell_feed_out = 890;

// Non-modal (group 0).
inline constexpr int G_4_dwell = 40;
inline constexpr int G_5_3_nurbs_end = 53;
inline constexpr int G_10_set_offsets = 100;
inline constexpr int G_25_spindle_min = 250;  // Sinumerik G25 S..
inline constexpr int G_26_spindle_max = 260;  // Sinumerik G26 S..
inline constexpr int G_28_home = 280;
inline constexpr int G_28_1_set_home = 281;
inline constexpr int G_30_home_2 = 300;
inline constexpr int G_30_1_set_home_2 = 301;
inline constexpr int G_52_local_origin = 520;
inline constexpr int G_53_machine_coordinates = 530;
inline constexpr int G_65_macro_call = 650;  // Fanuc
inline constexpr int G_92_set_position = 920;
inline constexpr int G_92_1_clear_position = 921;
inline constexpr int G_92_2_suspend_position = 922;
inline constexpr int G_92_3_restore_position = 923;
inline constexpr int G_117_position_output = 1170;  // Mazak

// Planes, units, distance, feed and return modes.
inline constexpr int G_17_plane_xy = 170;
inline constexpr int G_18_plane_xz = 180;
inline constexpr int G_20_inch = 200;
inline constexpr int G_70_inch = 700;    // Sinumerik (Fanuc's old inch code is refused)
inline constexpr int G_700_inch = 7000;  // Sinumerik: F in inches too
inline constexpr int G_90_absolute = 900;
inline constexpr int G_90_1_arc_absolute = 901;
inline constexpr int G_93_inverse_time = 930;
inline constexpr int G_95_per_revolution = 950;
inline constexpr int G_99_retract_to_r = 990;

// Cutter compensation and tool length.
inline constexpr int G_40_compensation_off = 400;
inline constexpr int G_41_compensation_left = 410;
inline constexpr int G_41_1_compensation_left_dynamic = 411;
inline constexpr int G_42_compensation_right = 420;
inline constexpr int G_42_1_compensation_right_dynamic = 421;
inline constexpr int G_43_tool_length = 430;
inline constexpr int G_43_1_tool_length_dynamic = 431;
inline constexpr int G_43_2_tool_length_added = 432;
inline constexpr int G_49_tool_length_off = 490;

// Work systems, path control, tilted planes.
inline constexpr int G_54_work_1 = 540;
inline constexpr int G_54_1_work_extended = 541;  // Fanuc G54.1 P..
inline constexpr int G_55_work_2 = 550;
inline constexpr int G_56_work_3 = 560;
inline constexpr int G_57_work_4 = 570;
inline constexpr int G_58_work_5 = 580;
inline constexpr int G_59_work_6 = 590;
inline constexpr int G_59_1_work_7 = 591;
inline constexpr int G_59_2_work_8 = 592;
inline constexpr int G_59_3_work_9 = 593;
inline constexpr int G_64_path_blending = 640;
inline constexpr int G_68_2_tilted_plane = 682;  // Fanuc
inline constexpr int G_69_rotation_off = 690;    // Fanuc

// M codes.
inline constexpr int M_0_stop = 0;
inline constexpr int M_1_optional_stop = 10;
inline constexpr int M_2_end = 20;
inline constexpr int M_3_spindle_cw = 30;
inline constexpr int M_4_spindle_ccw = 40;
inline constexpr int M_5_spindle_stop = 50;
inline constexpr int M_6_tool_change = 60;
inline constexpr int M_7_mist = 70;
inline constexpr int M_8_flood = 80;
inline constexpr int M_19_spindle_orient = 190;
inline constexpr int M_30_end_rewind = 300;
inline constexpr int M_50_feed_override = 500;
inline constexpr int M_53_feed_stop = 530;
inline constexpr int M_60_pallet_change = 600;
inline constexpr int M_61_set_tool = 610;
inline constexpr int M_62_digital_output_sync = 620;
inline constexpr int M_66_wait_input = 660;
inline constexpr int M_67_analog_output_sync = 670;
inline constexpr int M_68_analog_output = 680;
inline constexpr int M_98_call = 980;
inline constexpr int M_99_return = 990;

}  // namespace vcpost::gcode
