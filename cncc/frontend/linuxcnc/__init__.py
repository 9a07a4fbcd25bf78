"""LinuxCNC's rs274ngc language: O-word control flow, named parameters, messages.

``executor.run_linuxcnc`` runs a program; ``builder`` holds the syntax builders the
parser mixes in for ``cncc/grammar/rs274ngc.lark``; ``evaluate`` the expression
semantics (LinuxCNC's precedence, no vacant values, named parameters).
"""
