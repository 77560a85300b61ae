// A small Klartext program and the program as `vcpost post` writes it back
// (a TOOL CALL's S changed, TOOL CALL S blocks inserted, renumbered, F
// changed, every other byte kept: CRLF, a comment byte that is not UTF-8, a
// `~` continued cycle), worked out by hand: the patcher's tests write the
// one from the other, verify's prove the pair.
#pragma once

#include <string>

namespace vcpost::testing {

// Blocks 8-16 of both: cycle 200 on `~` continued lines.
inline const std::string kKlartextCycle200 =
    " CYCL DEF 200 DRILLING ~\r\n"
    "    Q200=2 ;SET-UP CLEARANCE ~\r\n"
    "    Q201=-5 ;DEPTH ~\r\n"
    "    Q206=150 ;FEED RATE FOR PLUNGING ~\r\n"
    "    Q202=5 ;PLUNGING DEPTH ~\r\n"
    "    Q210=0 ;DWELL TIME AT TOP ~\r\n"
    "    Q203=0 ;SURFACE COORDINATE ~\r\n"
    "    Q204=50 ;2ND SET-UP CLEARANCE ~\r\n"
    "    Q211=0 ;DWELL TIME AT BOTTOM\r\n";

inline const std::string kKlartextInput =
    "1 BEGIN PGM T MM\r\n"
    "2 ; K\xf6rivek\r\n"
    "3 FN 0: Q1=500\r\n"
    "4 TOOL CALL 5 Z S2500 DL+0\r\n"
    "5 L X+0 Y+0 Z+5 R0 FMAX M3\r\n"
    "6 L Z-1 F200\r\n"
    "7 L X+10 FQ1\r\n"
    "8" +
    kKlartextCycle200 +
    "9 L X+20 F300\r\n"
    "10 END PGM T MM\r\n";

// S3000 in block 4, S3100 before block 6 (with F250), S3200 before block 9.
inline const std::string kKlartextPosted =
    "1 BEGIN PGM T MM\r\n"
    "2 ; K\xf6rivek\r\n"
    "3 FN 0: Q1=500\r\n"
    "4 TOOL CALL 5 Z S3000 DL+0\r\n"
    "5 L X+0 Y+0 Z+5 R0 FMAX M3\r\n"
    "6 TOOL CALL S3100\r\n"
    "7 L Z-1 F250\r\n"
    "8 L X+10 FQ1\r\n"
    "9" +
    kKlartextCycle200 +
    "10 TOOL CALL S3200\r\n"
    "11 L X+20 F300\r\n"
    "12 END PGM T MM\r\n";

}  // namespace vcpost::testing
