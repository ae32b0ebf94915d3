"""Leave-one-trial-out cross-validation of settings chosen on data.

Every setting of a method that is chosen on recordings (not from the sensor's datasheet or its identified
noise) is chosen here without the recording it is scored on: for each trial, the setting with the lowest
mean score over the *other* trials is applied to it (held out); the in-sample figure is the setting with the
lowest mean over all trials, applied to each. The gap between the two is what choosing on the data is worth
on data it has not seen.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Dict, Hashable, List, Sequence

import numpy as np


@dataclass(frozen=True)
class Choice:
    """One trial's held-out figure: the setting chosen on the other trials and its score on this one."""

    trial: str
    setting: Hashable
    held_out: float
    in_sample: float


@dataclass(frozen=True)
class Result:
    """Held-out and in-sample figures of every trial; `in_sample_setting` is the one chosen on all."""

    choices: List[Choice]
    in_sample_setting: Hashable

    @property
    def held_out_mean(self) -> float:
        return float(np.mean([c.held_out for c in self.choices]))

    @property
    def in_sample_mean(self) -> float:
        return float(np.mean([c.in_sample for c in self.choices]))

    def settings_chosen(self) -> Dict[Hashable, int]:
        """How many folds chose each setting."""
        out: Dict[Hashable, int] = {}
        for c in self.choices:
            out[c.setting] = out.get(c.setting, 0) + 1
        return out


def leave_one_out(scores: Dict[Hashable, Dict[str, float]], trials: Sequence[str]) -> Result:
    """`scores[setting][trial]`: a lower-is-better score per trial (NaN: the setting failed there, never
    chosen by a fold that sees it). Ties go to the first setting in `scores`' order."""
    settings = list(scores)
    table = np.array([[scores[s][t] for t in trials] for s in settings], dtype=float)
    table = np.where(np.isfinite(table), table, np.inf)
    best_all = int(np.argmin(table.mean(axis=1)))
    choices = []
    for k, t in enumerate(trials):
        others = np.delete(table, k, axis=1).mean(axis=1)
        pick = int(np.argmin(others))
        choices.append(Choice(t, settings[pick], float(table[pick, k]), float(table[best_all, k])))
    return Result(choices, settings[best_all])
