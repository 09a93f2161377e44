"""Read the results of a dfc run (the HDF5 file the coupler writes, format "dfc-results-1").

    from dfc_results import open_results, open_variants

    with open_results("results/demo_pile/results.h5") as run:
        force = run.series("dem_pile_force_n")        # Series(name, values, unit, unit_guessed)
        print(force.unit, force.values.max())
        floor = run.series("dem_wall_floor_force_n")   # an [x, y, z] monitor: values of shape (rows, 3)
        for snap in run.snapshots("dem"):              # every DEM snapshot, in order
            print(snap.step, snap.time, snap.arrays["position"].shape)

    runs = open_variants("results/ucs_upscaling")      # {label: Results}, one per variant
    for label, run in runs.items():
        print(label, run.series("dem_axial_stress_pa").values.max())

Layout of the file (see docs/outputs.md):

    /                         attributes: format, created_utc, scenario (JSON text), versions (JSON),
                              summary (JSON, at the end of a run), failure (JSON, only when it failed)
    /timeseries/<column>      float64, one row per recorded exchange: 1-D for a number, (rows, 3)
                              for an [x, y, z] monitor; attribute "unit" (as the solver declared it),
                              and "unit_source" where the unit was only guessed from the name;
                              the group's attribute "columns" lists the columns in recorded order (JSON)
    /snapshots/<role>/<nnnnnn>  one group per snapshot of a participant ("dem", "continuum", ...):
                              attributes step, time, kind; one dataset per array; the role's
                              group has the attribute wall_names (JSON) where the server names its walls
    /xdmf/...                 index arrays for the ParaView sidecar (not read here)

Needs numpy and h5py (Debian: python3-numpy python3-h5py).
"""
import json
import os
from collections import OrderedDict
from typing import NamedTuple

# A coupler still writing the file holds the HDF5 file lock; reading without it
# shows what the coupler last flushed. Must be set before h5py is imported.
os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")

import h5py  # noqa: E402
import numpy as np  # noqa: E402

__all__ = ["FORMAT", "Results", "Series", "Snapshot", "open_results", "open_variants", "open_to_add_groups", "ResultsError"]

FORMAT = "dfc-results-1"
RESULTS_FILE = "results.h5"


class ResultsError(Exception):
    """The file is missing, not HDF5, or lacks what was asked for (the message says which)."""


class Series(NamedTuple):
    """One time-series column: its values (float64, shape (rows,) or (rows, 3) for a
    vector; NaN where the quantity does not apply in a row), its unit as the writer
    recorded it ("" when none was given), and whether that unit is only a guess from
    the column's name (a solver that declared no units)."""

    name: str
    values: np.ndarray
    unit: str
    unit_guessed: bool = False


class Snapshot(NamedTuple):
    """One snapshot of one participant. `arrays` maps the array name to a numpy array
    of the dtype and shape the server sent."""

    role: str
    index: int
    step: int
    time: float
    kind: str
    arrays: dict


def _text(value):
    if isinstance(value, bytes):
        return value.decode("utf-8")
    return str(value)


def _json_attribute(attrs, name):
    if name not in attrs:
        return None
    return json.loads(_text(attrs[name]))


class Results:
    """An open results file. Use it as a context manager, or call close().

    Everything returned is a copy in memory, still valid after the file is closed."""

    def __init__(self, path):
        self.path = os.fspath(path)
        if not os.path.isfile(self.path):
            raise ResultsError(f"no such results file '{self.path}'")
        try:
            self._file = h5py.File(self.path, "r")
        except OSError as error:
            raise ResultsError(f"cannot read '{self.path}' as HDF5 ({error})") from error
        attrs = self._file.attrs
        self.format = _text(attrs["format"]) if "format" in attrs else ""
        self.created_utc = _text(attrs["created_utc"]) if "created_utc" in attrs else ""
        self.scenario = _json_attribute(attrs, "scenario")
        self.versions = _json_attribute(attrs, "versions")

    # Metadata ---------------------------------------------------------------

    @property
    def name(self):
        """The scenario's name (a variant's is "<name>_<label>"), else the folder's name."""
        if isinstance(self.scenario, dict) and isinstance(self.scenario.get("name"), str):
            return self.scenario["name"]
        return os.path.basename(os.path.dirname(os.path.abspath(self.path)))

    @property
    def summary(self):
        """The run's closing summary (dict), or None while the run is still going."""
        return _json_attribute(self._file.attrs, "summary")

    @property
    def failure(self):
        """The failure message of a run that stopped on an error, else None."""
        return _json_attribute(self._file.attrs, "failure")

    @property
    def ended(self):
        """Whether the run that writes this file has ended (summary, failure or interruption
        written), so that the coupler no longer holds it open."""
        return _has_ended(self._file)

    # Time series ------------------------------------------------------------

    def _timeseries(self):
        group = self._file.get("timeseries")
        return group if isinstance(group, h5py.Group) else None

    @property
    def series_names(self):
        """Column names in the order the coupler recorded them ([] when none)."""
        group = self._timeseries()
        if group is None:
            return []
        declared = _json_attribute(group.attrs, "columns") or []
        present = [name for name, item in group.items() if isinstance(item, h5py.Dataset) and item.ndim in (1, 2)]
        ordered = [name for name in declared if name in present]
        return ordered + sorted(set(present) - set(ordered))

    def has_series(self, name):
        return name in self.series_names

    def series(self, name):
        """The column `name` as a Series; ResultsError naming the columns present if absent."""
        group = self._timeseries()
        dataset = group.get(name) if group is not None else None
        if not isinstance(dataset, h5py.Dataset):
            have = ", ".join(self.series_names) or "none"
            raise ResultsError(f"'{self.path}' has no time series '{name}' (have: {have})")
        unit = _text(dataset.attrs["unit"]) if "unit" in dataset.attrs else ""
        return Series(name, np.asarray(dataset[...], dtype=float), unit, "unit_source" in dataset.attrs)

    def unit(self, name):
        return self.series(name).unit

    def all_series(self):
        """Every column: {name: Series}, in recorded order."""
        return OrderedDict((name, self.series(name)) for name in self.series_names)

    # Snapshots --------------------------------------------------------------

    def _role_group(self, role):
        snapshots = self._file.get("snapshots")
        group = snapshots.get(role) if isinstance(snapshots, h5py.Group) else None
        if not isinstance(group, h5py.Group):
            raise ResultsError(f"'{self.path}' has no snapshots of '{role}' (have: {', '.join(self.roles) or 'none'})")
        return group

    @property
    def roles(self):
        """The participants that wrote snapshots ("dem", "continuum", ...)."""
        snapshots = self._file.get("snapshots")
        if not isinstance(snapshots, h5py.Group):
            return []
        return sorted(name for name, item in snapshots.items() if isinstance(item, h5py.Group))

    def snapshot_count(self, role):
        return len(self._role_group(role))

    def snapshot(self, role, index):
        """Snapshot number `index` of `role` (0 = first; negative counts from the end)."""
        group = self._role_group(role)
        names = sorted(group)
        try:
            name = names[index]
        except IndexError:
            raise ResultsError(f"'{self.path}' has {len(names)} snapshots of '{role}'; no index {index}") from None
        snap = group[name]
        arrays = {key: np.asarray(item[...]) for key, item in snap.items() if isinstance(item, h5py.Dataset)}
        return Snapshot(role, int(name), int(snap.attrs.get("step", -1)), float(snap.attrs.get("time", np.nan)),
                        _text(snap.attrs.get("kind", "")), arrays)

    def snapshots(self, role):
        """Every snapshot of `role`, in the order written."""
        return [self.snapshot(role, index) for index in range(self.snapshot_count(role))]

    def wall_names(self, role):
        """The names of `role`'s walls, indexed by a snapshot's wall_facet_wall
        ("floor", "pile", ..., "coupling surface"); [] where the file has none."""
        names = _json_attribute(self._role_group(role).attrs, "wall_names")
        return list(names) if isinstance(names, list) else []

    # File -------------------------------------------------------------------

    def close(self):
        if self._file is not None:
            self._file.close()
            self._file = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        return f"Results('{self.path}')"


_END_ATTRIBUTES = ("summary", "failure", "interrupted")  # the coupler's last word before it closes the file


def _has_ended(handle):
    return any(name in handle.attrs for name in _END_ATTRIBUTES)


def open_to_add_groups(path):
    """results.h5 opened read-write (an h5py.File) for a tool to add the groups it derives
    (/profiles/, /open_pile/, ...), or None while the run that writes it has not ended.

    The coupler keeps the file open for the whole run without the HDF5 file lock (so that
    readers can look in); a second writer then would corrupt it, losing the run's records.
    A run killed before its summary (no end attribute ever) gets no groups: rerun or
    resume it to the end first."""
    path = os.fspath(path)
    try:
        with h5py.File(path, "r") as handle:
            if not _has_ended(handle):
                return None
        return h5py.File(path, "r+")
    except OSError as error:
        raise ResultsError(f"cannot open '{path}' to add groups ({error})") from error


def open_results(path):
    """Open one results file (a path to results.h5, or to the folder that holds it)."""
    path = os.fspath(path)
    if os.path.isdir(path):
        path = os.path.join(path, RESULTS_FILE)
    return Results(path)


def open_variants(directory, scenario=None):
    """The runs of a scenario with `variants`, {label: Results}: every <directory>/<label>/results.h5.

    Ordered as the scenario file's `variants` list when `scenario` (its JSON path) is
    given, else by label. Close each Results when done."""
    directory = os.fspath(directory)
    if not os.path.isdir(directory):
        raise ResultsError(f"no such results folder '{directory}'")
    found = sorted(entry for entry in os.listdir(directory)
                   if os.path.isfile(os.path.join(directory, entry, RESULTS_FILE)))
    if scenario is not None:
        with open(scenario, encoding="utf-8") as handle:
            labels = [variant.get("label") for variant in json.load(handle).get("variants", [])]
        missing = [label for label in labels if label not in found]
        if missing:
            raise ResultsError(f"'{directory}' has no results of the variants {', '.join(missing)}")
        found = labels
    if not found:
        raise ResultsError(f"'{directory}' holds no <label>/{RESULTS_FILE} (is it the output folder of a scenario with variants?)")
    return OrderedDict((label, Results(os.path.join(directory, label, RESULTS_FILE))) for label in found)
