"""Leave-one-trial-out cross-validation of settings chosen on data.

Every setting of a method that is chosen on recordings (not from the sensor's datasheet or its identified
noise) is chosen here without the recording it is scored on: for each trial, the setting with the lowest
mean score over the *other* trials is applied to it (held out); the in-sample figure is the setting with the
lowest mean over all trials, applied to each. The gap between the two is what choosing on the data is worth
on data it has not seen.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Dict, Hashable, List, Sequence

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
    """`scores[setting][trial]`: a lower-is-better score per trial, the objective their mean (NaN: the
    setting failed there, never chosen by a fold that sees it). Ties go to the first setting in `scores`'
    order."""

    def objective(setting: Hashable, training: Sequence[str]) -> float:
        values = np.array([scores[setting][t] for t in training], dtype=float)
        return float(np.mean(values)) if np.all(np.isfinite(values)) else np.inf

    return leave_one_out_by(list(scores), trials, objective, lambda s, t: float(scores[s][t]))


def leave_one_out_by(
    settings: Sequence[Hashable],
    trials: Sequence[str],
    objective: Callable[[Hashable, Sequence[str]], float],
    score: Callable[[Hashable, str], float],
) -> Result:
    """The general form: `objective(setting, training_trials)` (lower is better; `inf`: not admissible
    on those trials) chooses; `score(setting, trial)` is what is reported for a trial."""
    trials = list(trials)

    def choose(training: Sequence[str]) -> Hashable:
        values = [objective(s, training) for s in settings]
        return settings[int(np.argmin(values))]

    best_all = choose(trials)
    choices = []
    for k, t in enumerate(trials):
        pick = choose(trials[:k] + trials[k + 1:])
        choices.append(Choice(t, pick, score(pick, t), score(best_all, t)))
    return Result(choices, best_all)
