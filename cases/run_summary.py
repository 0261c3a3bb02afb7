"""Reading a grains run's summary.json from the cases' analysis scripts."""


def stress_summary(summary):
    """The output.stress stage's part of summary.json (its means, average_after_s)."""
    for key, value in summary["stage_details"].items():
        if "output.stress" in key:
            return value["stress"]
    raise SystemExit("summary.json has no output.stress")
