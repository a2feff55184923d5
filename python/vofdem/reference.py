"""Reference data of a scene: what was observed on this weir (or a model's results for it), with the
sources, so that a run's reports compare with it. Optional: a scene without a ``[reference]`` table
compares with nothing, and its reports name no source.

Scene keys (``[reference]``, all optional):

* ``citation`` (text): where the observations come from; required as soon as one is given.
* ``first_removal_lps`` [l/s]: the discharge at which the first stone was removed.
* ``stage_lps`` [l/s]: the observed discharges of the destruction stages; ``stage_numbers`` which
  stages they are (default 1, 2, 3, ...); ``stage_times`` [s] when each began, on the clock of the
  rise: simulation time minus the spin-up (``hydrograph.ramp_start``); empty when not observed.
* ``note`` (text): one line printed under the comparison (e.g. how the values were read).
* the same for a model's results: ``model_citation``, ``model_first_removal_lps``,
  ``model_stage_numbers``, ``model_stage_lps``, ``model_stage_times``, ``model_note``.

The stage table (analysis.py), the ensemble's fragility table and figure (fragility.py) and the run's
figures (plots.py) take their reference lines from here only; the clock of the rise is shown only when
the reference has times.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Dict, List, Optional, Tuple

from .schema import _Section, _check_list, _fmt, _p

_Q = {"lo": 0.0, "hi": 1e6, "closed": "(]", "kind": "discharge"}
_T = {"lo": 0.0, "hi": 1e6, "closed": "[]", "kind": "time"}


def _text(default: str, doc: str):
    return field(default=default, metadata=dict(text=True, doc=doc))


@dataclass
class Reference(_Section):
    """Observed (and modelled) events of this weir under this flood, with their sources."""

    citation: str = _text("", "source of the observed values (required when one is given)")
    first_removal_lps: Optional[float] = _p(None, "discharge", 0.0, 1e6, "observed discharge of the first "
                                            "removal of a stone [l/s]", "(]")
    stage_numbers: List[int] = field(default_factory=list, metadata=dict(
        doc="which destruction stages stage_lps gives (default 1, 2, 3, ...)"))
    stage_lps: List[float] = field(default_factory=list, metadata=dict(doc="observed stage discharges [l/s]"))
    stage_times: List[float] = field(default_factory=list, metadata=dict(
        doc="observed stage start times [s] since the rise began (simulation time - spin-up); empty: none"))
    note: str = _text("", "a line printed under the comparison with the observations")
    model_citation: str = _text("", "source of a model's results for this weir (required when one is given)")
    model_first_removal_lps: Optional[float] = _p(None, "discharge", 0.0, 1e6, "the model's first removal "
                                                  "[l/s]", "(]")
    model_stage_numbers: List[int] = field(default_factory=list, metadata=dict(
        doc="which stages model_stage_lps gives (default 1, 2, 3, ...)"))
    model_stage_lps: List[float] = field(default_factory=list, metadata=dict(doc="the model's stage discharges [l/s]"))
    model_stage_times: List[float] = field(default_factory=list, metadata=dict(
        doc="the model's stage start times [s] since the rise began; empty: none"))
    model_note: str = _text("", "a line printed under the comparison with the model")

    def validate(self, prefix: str = "reference") -> None:
        self._validate_fields(prefix)
        for f in ("citation", "note", "model_citation", "model_note"):
            v = getattr(self, f)
            if not isinstance(v, str) or "\n" in v:
                raise ValueError(f"{prefix}.{f} = {v!r} must be a text of one line")
        for who in ("", "model_"):
            self._validate_source(prefix, who)

    def _validate_source(self, prefix: str, who: str) -> None:
        nums, qs, ts = (getattr(self, f"{who}stage_{k}") for k in ("numbers", "lps", "times"))
        _check_list(f"{prefix}.{who}stage_lps", qs, _Q)
        _check_list(f"{prefix}.{who}stage_times", ts, _T)
        _check_list(f"{prefix}.{who}stage_numbers", nums, {"lo": 1, "hi": 1000, "closed": "[]", "kind": None})
        for j, k in enumerate(nums):
            if k != int(k):
                raise ValueError(f"{prefix}.{who}stage_numbers[{j}] = {_fmt(k)} must be a whole number in [1, 1000]")
        setattr(self, f"{who}stage_numbers", [int(k) for k in nums])
        if nums and len(nums) != len(qs):
            raise ValueError(f"{prefix}.{who}stage_numbers has {len(nums)} entries, {prefix}.{who}stage_lps has "
                             f"{len(qs)}: they must match")
        if len(set(nums)) != len(nums):
            raise ValueError(f"{prefix}.{who}stage_numbers = {list(nums)} lists a stage twice")
        if ts and len(ts) != len(qs):
            raise ValueError(f"{prefix}.{who}stage_times has {len(ts)} entries, {prefix}.{who}stage_lps has "
                             f"{len(qs)}: they must match (or leave it empty)")
        given = bool(qs) or getattr(self, f"{who}first_removal_lps") is not None
        cite = f"{who}citation"
        if given and not getattr(self, cite).strip():
            raise ValueError(f"{prefix}.{cite} is required: the {'model results' if who else 'observed values'} "
                             f"in [{prefix}] need their source")

    # ------------------------------------------------------------------ queries
    @property
    def has_observed(self) -> bool:
        return bool(self.stage_lps) or self.first_removal_lps is not None

    @property
    def has_model(self) -> bool:
        return bool(self.model_stage_lps) or self.model_first_removal_lps is not None

    @property
    def given(self) -> bool:
        """Whether the scene compares with anything."""
        return self.has_observed or self.has_model

    @property
    def has_times(self) -> bool:
        """Whether any stage time is given (the reports then show the clock of the rise)."""
        return bool(self.stage_times) or bool(self.model_stage_times)

    def stages(self, model: bool = False) -> Dict[int, Tuple[float, Optional[float]]]:
        """{stage number: (discharge [l/s], start time on the clock of the rise [s] or None)}."""
        who = "model_" if model else ""
        qs, ts = getattr(self, f"{who}stage_lps"), getattr(self, f"{who}stage_times")
        nums = getattr(self, f"{who}stage_numbers") or list(range(1, len(qs) + 1))
        return {int(k): (float(q), float(ts[j]) if ts else None) for j, (k, q) in enumerate(zip(nums, qs))}

    def event_lps(self, event: str) -> Tuple[Optional[float], Optional[float]]:
        """(observed, model) discharge [l/s] of an event: 'first_removal' or 'stage<k>'; None where not given."""
        if event == "first_removal":
            return self.first_removal_lps, self.model_first_removal_lps
        k = int(event.removeprefix("stage"))
        obs, mod = self.stages().get(k), self.stages(model=True).get(k)
        return (obs[0] if obs else None), (mod[0] if mod else None)

    def without_times(self) -> "Reference":
        """A copy without stage times (a run whose discharge rises at another rate has another clock)."""
        import copy

        r = copy.deepcopy(self)
        r.stage_times, r.model_stage_times = [], []
        return r

    def short(self, model: bool = False) -> str:
        """The source's citation for a legend, cut to 48 characters."""
        text = (self.model_citation if model else self.citation).strip()
        return text if len(text) <= 48 else text[:45].rstrip() + "..."


def maeno2008_reference() -> Reference:
    """What Maeno & Tomita (2008) give for their weir: the experiment of Maeno et al. (2002) as they cite
    it (first removals at about 14 l/s, second stage 16.5 l/s, third 20.4 l/s), and their model's results
    (no removal before its second stage, at 17.1 l/s and 56.8 s after the rise began; third stage at
    19.2 l/s, 16 s later)."""
    return Reference(
        citation="experiment of Maeno et al. (2002), as cited by Maeno & Tomita (2008)",
        first_removal_lps=14.0, stage_lps=[14.0, 16.5, 20.4],
        note="the experiment's discharges are approximate (about 14 l/s for the first removals)",
        model_citation="VOF-DEM model of Maeno & Tomita (2008)",
        model_stage_numbers=[2, 3], model_stage_lps=[17.1, 19.2], model_stage_times=[56.8, 72.8],
        model_note="the model removed no stone before its second stage (stones vibrated from 15 l/s)")


def format_lps(q: Optional[float], t: Optional[float] = None) -> str:
    """'17.10 (56.8)' or '14' style cell of a comparison table; '-' when not given."""
    if q is None or (isinstance(q, float) and math.isnan(q)):
        return "-"
    return f"{q:g}" + (f" ({t:g})" if t is not None else "")

