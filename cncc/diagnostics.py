"""Diagnostics: stable codes, severities, a sink that every stage reports into.

Stages emit and carry on; exceptions are for bugs only.  The table of codes lives
here so that ``docs/diagnostics.md`` can be generated from it (see
``python -m cncc.tools.gendocs``).

Code ranges: E01xx lexical and syntax, E02xx modal interpretation, E03xx macros and
subprograms, E04xx canned cycles, E05xx frames and compensation, E06xx machine models,
planning and verification, E07xx pulses, E08xx translation, E09xx driver and files.
"""

from __future__ import annotations

import enum
from collections.abc import Iterator
from dataclasses import dataclass

from cncc.source import Span


class Severity(enum.IntEnum):
    NOTE = 0
    WARNING = 1
    ERROR = 2

    @property
    def label(self) -> str:
        return self.name.lower()


@dataclass(frozen=True, slots=True)
class CodeInfo:
    code: str
    severity: Severity
    summary: str


CODES: dict[str, CodeInfo] = {}


def _define(code: str, severity: Severity, summary: str) -> str:
    if code in CODES:  # pragma: no cover - programming error
        raise ValueError(f"duplicate diagnostic code {code}")
    CODES[code] = CodeInfo(code, severity, summary)
    return code


E, W, N = Severity.ERROR, Severity.WARNING, Severity.NOTE

# --- E01xx: lexical and syntax -------------------------------------------------
SYNTAX = _define("E0101", E, "the block does not follow the dialect's grammar")
BAD_NUMBER = _define("E0102", E, "a number is malformed (e.g. two decimal points)")
BAD_NUMBER_LENIENT = _define("W0102", W, "a malformed number was accepted in lenient mode")
UNCLOSED_COMMENT = _define("W0103", W, "a '(' comment is not closed before the end of the line")
BAD_CHARACTER = _define("E0104", E, "a character that no G-code dialect uses")
NUMBER_RANGE = _define("E0105", E, "a number is out of the range its address accepts")
LINE_TOO_LONG = _define("E0106", E, "a line is longer than the front end accepts")
EMPTY_PROGRAM = _define("W0107", W, "the program contains no blocks")
MISSING_VALUE = _define("E0108", E, "an address letter has no value")
DECIMAL_NOT_ALLOWED = _define("E0109", E, "a decimal point is written where the address takes an integer")
FULLWIDTH = _define("W0110", W, "full-width punctuation (as in some manuals) was read as its ASCII form")
EXPONENT_NUMBER = _define("E0160", E, "a number in exponent notation (1e3), which no controller reads; "
                          "block skipped")
IR_TEXT_SYNTAX = _define("E0194", E, "IR text (cncc.ir.text) that does not follow its format")
IR_TEXT_NAME = _define("E0195", E, "IR text that names a command, type, field or frame the IR does not have, "
                       "or gives a field a value of the wrong type")
NUMBER_OVERFLOW = _define("E0161", E, "a number too large for any controller (13 or more integer digits); "
                          "block skipped")

# --- E02xx: modal interpretation -------------------------------------------------
UNKNOWN_G = _define("E0201", E, "a G code that the dialect does not define")
UNKNOWN_M = _define("E0202", E, "an M code that the dialect does not define")
MODAL_CONFLICT = _define("E0203", E, "two codes of the same modal group in one block")
NOT_SUPPORTED = _define("E0204", E, "a code the dialect defines but cncc does not implement yet")
REPEATED_WORD = _define("E0205", E, "the same address appears twice in a block")
UNUSED_WORD = _define("W0206", W, "a word that no code in the block uses")
ARC_NO_CENTER = _define("E0207", E, "an arc has neither I/J/K nor R")
ARC_RADIUS = _define("E0208", E, "an arc's start and end are not at the same distance from its centre")
ARC_R_TOO_SMALL = _define("E0209", E, "an R arc whose radius is less than half the chord")
ARC_R_FULL_CIRCLE = _define("E0210", E, "an R arc cannot describe a full circle")
NO_FEED = _define("E0211", E, "a feed move without a feed rate")
DEFAULT_FEED = _define("N0212", N, "no F programmed yet; the dialect's default feed is used")
BAD_DWELL = _define("E0213", E, "a dwell time is missing or negative")
TOO_MANY_M = _define("E0214", E, "more M codes in a block than the dialect allows")
BAD_OFFSET_INDEX = _define("E0215", E, "a work, tool or reference index out of range")
ARC_ZERO_RADIUS = _define("E0219", E, "an arc whose centre is its start point")
G53_INCREMENTAL = _define("W0216", W, "G53 in incremental mode is ignored")
AFTER_END = _define("N0217", N, "blocks after the program end are not executed")
DECIMAL_P_DWELL = _define("W0218", W, "G04 P takes integer milliseconds; the fraction is dropped")

# --- E025x: dialect conformance (issue 11: grbl, LinuxCNC, SERIES 8, detection) ----------
ONE_SPINDLE = _define("W0273", W, "a spindle number ($) other than 0 that the INI file allows: cncc models one "
                      "spindle and runs the block's spindle codes on it")
CONTROLLER_REJECTS = _define("E0250", E, "the controller rejects the block; the message gives its own error text")
DIALECT_GUESSED = _define("N0251", N, "no -x given: the dialect was guessed from the file name and its contents")
SOURCE_INCONSISTENT = _define("W0252", W, "the controller's manual contradicts itself here; a dialect option decides")
INVALID_ARC = _define("E0253", E, "an arc the dialect cannot make (SERIES 8: signed I/J or more than one quadrant)")
DIALECT_IGNORED = _define("W0254", W, "a word or code the dialect's controller accepts and ignores")
VENDOR_CYCLE = _define("E0255", E, "a code the manual names without defining its words (SERIES 8 G34-G36, G43, "
                       "G49-G51): it needs a cycle macro")
ZERO_FEED = _define("E0260", E, "a feed move with F0 (the controller alarms); the move is not made")
DWELL_WITH_MOTION = _define("E0261", E, "G04 and a move in one block, where the controller reads the block's "
                            "axis words as the dwell's; neither is run")
AXIS_WORDS_TAKEN = _define("W0262", W, "a motion code in a block whose axis words another code takes (G92, G52, G10, "
                           "G51, G51.1, G68): the motion code sets the mode, nothing moves")
ASSUMED = _define("W0256", W, "the manual leaves this open; the spec's assumption is used (a dialect option)")
CORNER_INSERT = _define("E0257", E, "a G10 corner that cannot be inserted (next move not a line, setback too long, "
                        "no corner)")
CAVITY_BAD_WORD = _define("E0258", E, "a SERIES 8 G34-G36 cavity that cannot be milled (size, step-over, depth per "
                          "pass or tool radius missing or out of range)")

# --- shops (issue 23): real programs from real shops (band x70-x74) -------------------
M_CODE_TO_MACHINE = _define("W0270", W, "an M code the dialect does not define is passed to the machine (PMC/ladder)")
GUESS_CHANGES_NUMBERS = _define("W0271", W, "the guessed dialect reads integers in least input units (X10 = 0.010 mm); "
                                "-x confirms the dialect")
UNKNOWN_SYSTEM_VARIABLE = _define("W0370", W, "a system variable the dialect's table does not list (read vacant, write "
                                  "ignored)")
DEPENDS_ON_ARGUMENTS = _define("N0371", N, "a problem of a macro library or subprogram file linted without a caller "
                               "that depends on its arguments or modal state (F ...)")

# --- E04xx: canned cycles and hole patterns ----------------------------------------
CYCLE_NO_R = _define("E0401", E, "a drilling block without an R level")
CYCLE_NO_BOTTOM = _define("E0402", E, "a drilling block without a hole bottom (Z)")
CYCLE_R_PAST_BOTTOM = _define("E0403", E, "the R level is not on the entry side of the hole bottom")
CYCLE_BAD_PECK = _define("E0404", E, "a peck cycle without a positive depth per peck Q")
CYCLE_NEGATIVE_Q = _define("W0405", W, "a negative Q; its absolute value is used")
CYCLE_BAD_REPEAT = _define("E0406", E, "a repeat count (K or L) that is not an integer in range")
CYCLE_PLANE_CHANGE = _define("E0407", E, "the plane changed while a canned cycle is in force")
PATTERN_NO_CYCLE = _define("E0408", E, "a hole pattern without a canned cycle in force")
PATTERN_BAD_WORD = _define("E0409", E, "a hole-pattern word is missing or out of range")
CYCLE_R_ABOVE_INITIAL = _define("W0410", W, "the R level is farther out than the initial level")
CYCLE_REPEAT_ABSOLUTE = _define("W0411", W, "repeats in absolute mode drill the same hole again")
CYCLE_NO_PITCH = _define("E0412", E, "a tapping cycle without a pitch or a spindle speed")
CYCLE_BAD_SHIFT = _define("E0413", E, "a boring shift direction parameter out of range")
CYCLE_SPINDLE = _define("W0414", W, "a tapping cycle starts with the spindle off or turning the wrong way")
CYCLE_UNKNOWN = _define("E0415", E, "the dialect names a cycle kind cncc does not know")
CYCLE_WORDS_NOT_STORED = _define("W0416", W, "cycle data in a block that does not drill is not stored")
CYCLE_LONG_DWELL = _define("W0417", W, "a cycle dwell longer than a minute (is P in the right unit?)")
CYCLE_BACK_BORE_SWAPPED = _define("W0418", W, "a back bore with R above Z: the tool starts at the lower level")
CYCLE_RETURN_IN_HOLE = _define("E0419", E, "the level a cycle returns to is inside the hole (initial level too low)")
LATHE_PROFILE = _define("E0480", E, "a lathe cycle's profile (G70-G72 Q subroutine) cannot be cut: not monotonic, "
                        "a bad arc or corner, or no progress")
LATHE_GOUGE = _define("E0463", E, "a lathe cycle (G70-G72) refused: one of its moves would go into the finished "
                      "part (nothing of the cycle runs)")
LATHE_CYCLE_WORDS = _define("E0481", E, "a lathe cycle (G70-G72, G76) word is missing or out of range")
LATHE_CYCLE_STATE = _define("E0482", E, "a lathe cycle in a state it cannot run in (not G18, cutter compensation on)")

# --- E03xx: macros, variables and subprograms (cncc/frontend/macro) ----------------
MACRO_STEP_BUDGET = _define("E0301", E, "the program ran past the step budget (an endless loop or recursion?)")
MACRO_BAD_VARIABLE = _define("E0302", E, "a variable number that the macro language does not have")
MACRO_READ_ONLY = _define("E0303", E, "an assignment to a variable that cannot be written")
MACRO_DIV_ZERO = _define("E0304", E, "a division by zero in a macro expression")
MACRO_DOMAIN = _define("E0305", E, "a macro function called outside its domain (SQRT of a negative ...)")
MACRO_NO_LABEL = _define("E0306", E, "a jump to a sequence number that the program does not have")
MACRO_END_WITHOUT_DO = _define("E0307", E, "END n without a matching WHILE ... DO n")
MACRO_LOOP_MISMATCH = _define("E0308", E, "loops that cross, a DO without END, or a loop number out of range")
MACRO_NESTING = _define("E0309", E, "subprogram or macro calls nested deeper than the dialect allows")
MACRO_NO_PROGRAM = _define("E0310", E, "a called program is in neither this file nor an -I folder")
MACRO_ALARM = _define("E0311", E, "the program raised an alarm (#3000)")
MACRO_STOP_MESSAGE = _define("N0312", N, "the program stops with an operator message (#3006, MSG)")
MACRO_GOTO_INTO_LOOP = _define("E0313", E, "a jump into the body of a WHILE loop")
MACRO_FILE_NOT_WRITTEN = _define("W0314", W, "a program-writing statement without --write-dir writes nothing")
MACRO_FILE_REFUSED = _define("E0315", E, "a program-writing statement names a file outside --write-dir")
MACRO_BAD_CALL = _define("E0316", E, "a call with a bad program, count or argument")
MACRO_VACANT_WORD = _define("N0317", N, "a word whose value is a vacant variable is left out of the block")
MACRO_RESERVED = _define("W0318", W, "a write to a variable the controller reserves for itself")
MACRO_IF_STRUCTURE = _define("E0319", E, "ELSE, ELIF or ENDIF without IF, or an IF without ENDIF")
MACRO_NO_RETURN = _define("W0320", W, "a subprogram ends without M99; it returns at its end")
MACRO_BARE_ELIF = _define("W0321", W, "ELIF without a condition is taken as ELSE")
MACRO_BAD_VALUE = _define("E0322", E, "a macro value that is not a finite number, or out of range for its use")
MACRO_INPUT_TIMEOUT = _define("E0323", E, "a wait for an input that the --io file never makes valid")
MACRO_BAD_IO_FILE = _define("E0324", E, "the --io file is malformed")
MACRO_NOT_SUPPORTED = _define("E0325", E, "a macro feature cncc does not implement")

# --- E035x: LinuxCNC O-words and named parameters (cncc/frontend/linuxcnc) ------------------
OWORD_STRUCTURE = _define("E0350", E, "O-word control flow out of order (endwhile without while, no endsub ...)")
OWORD_NO_SUB = _define("E0351", E, "a call of an O-word subroutine that is neither defined nor found in an -I folder")
NAMED_UNDEFINED = _define("E0352", E, "a named parameter is read before it was set")
LINUXCNC_PRINT = _define("N0353", N, "the text of a LinuxCNC (PRINT,...) comment")
PROGRAM_NO_END = _define("E0326", E, "a LinuxCNC main program ends without M2/M30 or its closing %")
PROGRAM_ABORT = _define("E0327", E, "the program stopped at a LinuxCNC (ABORT,...) comment")
SUB_STYLE_MIXED = _define("E0386", E, "a LinuxCNC subroutine of one style (O100 ... M99 or o100 sub ... endsub) called "
                          "or ended the other style's way, or an M98/M99 that LinuxCNC does not read")

# --- E05xx: frames and compensation ------------------------------------------------
TRANSFORM_WORDS = _define("E0501", E, "a frame or compensation code lacks a word it needs, or a word is out of range")
SCALED_ARC_ELLIPSE = _define("E0502", E, "a transform would turn an arc into an ellipse or out of its plane")
COMP_ON_ARC = _define("E0503", E, "cutter compensation is started or cancelled on an arc (only G00/G01 may)")
COMP_GOUGE = _define("E0504", E, "cutter compensation interference: the offset path runs against the programmed one")
COMP_ARC_TOO_SMALL = _define("E0505", E, "an inside arc whose radius is smaller than the tool radius")
COMP_NO_INTERSECTION = _define("E0506", E,
                              "an inside corner whose offset elements do not meet (no room for the tool)")
COMP_CORNER_ARC = _define("W0507", W, "an outside corner whose offset elements do not meet; an arc is used")
COMP_LOOKAHEAD = _define("W0508", W, "too many moves without plane motion during compensation (over- or undercut)")
COMP_PLANE_CHANGE = _define("E0509", E, "the plane changed while cutter compensation is active")
TOOL_OFFSET_IN_COMP = _define("E0510", E, "G45-G48 tool offset while cutter compensation is active")
ARC_REPAIRED = _define("W0511", W, "an arc's centre was moved to make its radii agree")
DATA_INPUT = _define("E0512", E, "G10 with a table (L) or entry (P) that cncc does not know")
OFFSET_NOT_IN_TABLE = _define("W0513", W, "an H or D number that the tool table does not have; 0 is used")
COMP_REFUSES = _define("E0572", E, "a code (or a read of the current position) that the controller refuses "
                       "while cutter radius compensation is on; the block is not run")
COMP_NO_OFFSET = _define("W0560", W, "G41/G42 without an offset number (D): the controller runs it with radius 0")
TRANSFORM_DEFAULT = _define("W0514", W, "a frame code without a value the manual leaves to a parameter; a default used")

# --- E06xx: machine models, planning, verification --------------------------------
BAD_MACHINE = _define("E0601", E, "a machine model file or override is malformed (the message names the key)")
AXIS_NOT_ON_MACHINE = _define("E0602", E, "a move commands an axis the machine model does not have")
FEED_CLAMPED = _define("N0603", N, "the programmed feed is above the machine's feed cap and is clamped")
BAD_FEED = _define("E0604", E, "a feed move has a zero or negative feed rate")
PLAN_FALLBACK = _define("W0605", W, "the planner could not solve a window optimally and used a safer profile")
FEED_TOO_SMALL = _define("W0606", W, "a feed below the smallest one the planner handles is planned at that minimum")
VERIFY_VELOCITY = _define("E0610", E, "verify: an axis velocity exceeds its limit")
VERIFY_ACCEL = _define("E0611", E, "verify: an axis acceleration exceeds its limit")
VERIFY_JERK = _define("E0612", E, "verify: an axis jerk exceeds its limit")
VERIFY_PATH = _define("E0613", E, "verify: the trajectory leaves the programmed path by more than the tolerance")
VERIFY_FEED = _define("E0614", E, "verify: the path speed exceeds the programmed feed")
VERIFY_SOFT_LIMIT = _define("E0615", E, "verify: an axis leaves its soft limits")
VERIFY_CONTINUITY = _define("E0616", E, "verify: the trajectory jumps in position or time between phases")
VERIFY_CORNER = _define("E0617", E, "verify: a velocity step at a phase boundary exceeds the corner rule")
VERIFY_ACCEL_STEP = _define("E0618", E, "verify: an acceleration step at a phase boundary, spread over one "
                                        "interpolation period, exceeds the jerk limit")

# --- E069x: timing reports (cncc/backends/timing) ----------------------------------
TIME_CLAMPED = _define("W0690", W, "a time too long or not finite for the timing report was clamped")

# --- E07xx: pulses -------------------------------------------------------------
STEP_RATE = _define("E0701", E, "an axis would step faster than its maximum step rate")
PULSE_SPACING = _define("E0702", E, "two pulses of an axis closer than the minimum spacing (twice the pulse width)")
SOFT_LIMIT = _define("E0703", E, "the trajectory crosses an axis soft limit")
BAD_PITCH_TABLE = _define("E0704", E, "a pitch-error table would make the axis move backwards; the table is ignored")
DIR_SETUP_DELAY = _define("W0705", W, "a step was delayed to respect the direction set-up time")
AXIS_NOT_IN_MACHINE = _define("W0706", W, "a trajectory axis is not in the machine model; default step output used")
NO_OFFSETS_TABLE = _define("W0775", W, "soft limits crossed while no work offsets table is loaded: program positions "
                           "were checked as machine positions (one diagnostic for all such moves)")

# --- E08xx: translation (cncc/backends/gcode, --emit=gcode -t) --------------------
# The N08xx notes say what cncc did because the target cannot (or so the output is
# exact); under -Werror they are errors, for users who need the target to do it.
XL_ROTATION = _define("N0801", N, "coordinate rotation (G68) is written as rotated coordinates")
XL_SCALING = _define("N0802", N, "scaling is written as scaled coordinates")
XL_MIRROR = _define("N0803", N, "the programmable mirror is written as mirrored coordinates")
XL_POLAR = _define("N0804", N, "polar coordinates are written as Cartesian coordinates")
XL_COMP = _define("N0805", N, "cutter radius compensation is written as the compensated tool path")
XL_CYCLE_EXPANDED = _define("N0806", N, "a canned cycle is written as moves (the target has no equivalent cycle)")
XL_PATTERN = _define("N0807", N, "a hole pattern is written as a list of holes")
XL_SUBPROGRAMS = _define("N0808", N, "subprograms and macros are written flattened")
XL_FOLDED = _define("N0809", N, "an offset the target cannot set is folded into the coordinates")
XL_NO_CODE = _define("W0810", W, "the target has no code for an operation; it is written as a comment")
XL_LINE_LENGTH = _define("W0811", W, "a line is longer than the target control reads")
XL_LINE_NUMBER = _define("W0812", W, "a line number beyond the target's largest N")
XL_PROGRAM_NUMBER = _define("W0813", W, "a program number outside the target's range")
XL_NESTING = _define("W0814", W, "subprograms nest deeper than the target allows")
XL_WORD_RANGE = _define("W0815", W, "a word value beyond the target's range")
XL_TAP_UNSYNCED = _define("W0816", W, "a tapping cycle is written as plain moves (not spindle-synchronised)")
XL_ARC_SPLIT = _define("N0817", N, "arcs are split into pieces the target accepts")

# --- language server (cncc/lsp): target checks and the analysis budget ----------
XL_INCREMENT_UNKNOWN_START = _define("E0860", E, "a G91 move of an axis whose position the program has not set yet "
                                     "(start, tool change, reference return): the translation would write it "
                                     "from an assumed position")
XL_RETURN_START = _define("E0861", E, "a return to the program's start point (SZGH G26) that the target cannot write: "
                          "the start is wherever the machine was")
XL_NO_PROBE = _define("E0883", E, "a G38.x probe move the target dialect cannot write (it has no probing): the move "
                      "is not translated")
TARGET_UNSUPPORTED = _define("W0890", W, "a code the target dialect has no counterpart for")
ANALYSIS_STOPPED = _define("N0990", N, "the editor stopped analysing a document at its time budget")

# --- E09xx: driver and files --------------------------------------------------
CANNOT_READ = _define("E0901", E, "an input file cannot be read")
CANNOT_WRITE = _define("E0902", E, "an output file cannot be written")
BAD_OFFSETS_FILE = _define("E0903", E, "an offsets or tools file is malformed")
BAD_OPTION = _define("E0904", E, "a command-line option has a bad value")
WERROR = _define("E0905", E, "a warning turned into an error by -Werror")
OUTPUT_IS_INPUT = _define("E0906", E, "the output file would overwrite an input file")
SETTING_ORIGIN = _define("N0907", N, "-v: where a setting came from (command line, modeline, cncc.toml, default)")
BAD_PROJECT_CONFIG = _define("E0908", E, "a cncc.toml project file is malformed")
NUMPY_WARNING = _define("W0909", W, "a numerical warning (overflow, invalid value) raised while computing")
INI_UNREADABLE = _define("E0983", E, "the --ini file cannot be read")
INI_BAD_VALUE = _define("W0972", W, "an --ini value that LinuxCNC refuses (out of its range, not a number); "
                        "the dialect's default is kept, as LinuxCNC keeps its own")
INI_BAD_LINE = _define("E0984", E, "a line of the --ini file is not a section, a NAME = VALUE line or a comment")
BAD_PASS_SPEC = _define("E0991", E, "-p, --print-after: an unknown pass, an unknown option or a bad value")
PASSES_OMITTED = _define("W0973", W, "-p leaves out path passes the output needs (cycles, frames, machine "
                                     "coordinates): the output is not the program's motion")
IR_INVARIANT = _define("E0992", E, "--verify-each: a pass broke an IR invariant (continuity, spans, machine frame)")

# dialect data (E0940-E0944)
UNKNOWN_FRONT_END = _define("E0940", E, "the dialect file names a front end that is not registered")

# --- E0995-E0999: program libraries (cncc batch) ---------------------------------
BATCH_NO_PROGRAMS = _define("E0995", E, "batch: no program file matches the given folders and patterns")
BATCH_TIME_LIMIT = _define("E0996", E, "batch: a program ran over its time limit")
BATCH_MEMORY_LIMIT = _define("E0997", E, "batch: a program ran over its memory limit")
BATCH_CRASH = _define("E0998", E, "batch: the compiler crashed on a program, or its process died")
BATCH_RESULTS = _define("E0999", E, "batch: the results file or the cluster cannot be used")


@dataclass(frozen=True, slots=True)
class Related:
    span: Span
    message: str


@dataclass(frozen=True, slots=True)
class Diagnostic:
    code: str
    severity: Severity
    span: Span
    message: str
    related: tuple[Related, ...] = ()


@dataclass(frozen=True, slots=True)
class WarningPolicy:
    """What the command line's -w, -Wno-CODE, -Werror=CODE and -fmax-errors=N ask of a sink."""

    disabled: frozenset[str] = frozenset()  # -Wno-CODE: not reported
    as_errors: frozenset[str] = frozenset()  # -Werror=CODE: reported as errors
    no_warnings: bool = False  # -w: no warnings reported
    max_errors: int = 0  # -fmax-errors=N: errors after the N-th are dropped (0: no limit)


class DiagnosticSink:
    """Collects diagnostics from every stage; never raises."""

    def __init__(self, *, werror: bool = False, max_count: int = 10_000,
                 policy: WarningPolicy | None = None) -> None:
        self.items: list[Diagnostic] = []
        self.werror = werror
        self.max_count = max_count
        self.dropped = 0
        self.policy = policy or WarningPolicy()
        self.suppressed = 0  # diagnostics -w / -Wno-CODE kept quiet
        self.errors_kept = 0
        self.over_limit = 0  # errors dropped past -fmax-errors

    def emit(
        self,
        code: str,
        span: Span,
        message: str,
        related: tuple[Related, ...] = (),
        severity: Severity | None = None,
    ) -> None:
        if severity is None:
            info = CODES.get(code)
            severity = info.severity if info is not None else Severity.ERROR
        pol = self.policy
        if code in pol.disabled or (pol.no_warnings and severity is Severity.WARNING):
            self.suppressed += 1
            return
        if (self.werror and severity is Severity.WARNING) or code in pol.as_errors:
            severity = Severity.ERROR
        if severity is Severity.ERROR and pol.max_errors and self.errors_kept >= pol.max_errors:
            self.over_limit += 1
            return
        if len(self.items) >= self.max_count:
            self.dropped += 1
            return
        if severity is Severity.ERROR:
            self.errors_kept += 1
        self.items.append(Diagnostic(code, severity, span, message, related))

    @property
    def limit_reached(self) -> bool:
        """-fmax-errors=N: N errors were reported (the run may stop here)."""
        return bool(self.policy.max_errors) and self.errors_kept >= self.policy.max_errors

    def __iter__(self) -> Iterator[Diagnostic]:
        return iter(self.items)

    def __len__(self) -> int:
        return len(self.items)

    @property
    def error_count(self) -> int:
        return sum(1 for d in self.items if d.severity is Severity.ERROR)

    @property
    def has_errors(self) -> bool:
        return any(d.severity is Severity.ERROR for d in self.items)
