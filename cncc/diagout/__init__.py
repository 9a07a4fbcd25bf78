"""Machine-readable diagnostics: ``-fdiagnostics-format=json`` (:mod:`.jsonout`, own schema)
and ``-fdiagnostics-format=sarif`` (:mod:`.sarif`, SARIF 2.1.0)."""

from __future__ import annotations

from cncc.diagout.locate import Place, place

FORMATS = ("text", "json", "sarif")

__all__ = ["FORMATS", "Place", "place"]
