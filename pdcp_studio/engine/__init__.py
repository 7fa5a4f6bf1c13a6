"""The device profile layer (thesis chapter 4) as a pure engine that returns plans.

Nothing here does I/O or imports Qt, python-can or networkx; every ``plan_*`` function
reads a ``System`` without changing it and returns a ``Plan`` to preview, explain, diff
and ``apply``. The algorithms follow reference §2 and its Decisions exactly.
"""

from pdcp_studio.engine.checks import Finding, Severity, check_system
from pdcp_studio.engine.layer import Connected, ProfileLayer
from pdcp_studio.engine.modes import (
    EXTRA_MODES,
    MODES,
    plan_autoconfigure,
    plan_clear,
    plan_duty_cycle,
    plan_enforce,
    plan_for,
    plan_implement,
    plan_on_bus,
    plan_replacements,
    plan_startup,
)
from pdcp_studio.engine.plan import (
    Action,
    Attempt,
    ChannelFacts,
    Op,
    Plan,
    Refusal,
    Rejection,
    Rule,
    set_links,
)
from pdcp_studio.engine.procedures import (
    choose_configuration,
    configuration_from_system,
    resolve_configuration,
    retrieve_configuration,
)
from pdcp_studio.engine.similarity import Similarity, determine_similarity

__all__ = [
    "EXTRA_MODES",
    "MODES",
    "Action",
    "Attempt",
    "ChannelFacts",
    "Connected",
    "Finding",
    "Op",
    "Plan",
    "ProfileLayer",
    "Refusal",
    "Rejection",
    "Rule",
    "Severity",
    "Similarity",
    "check_system",
    "choose_configuration",
    "configuration_from_system",
    "determine_similarity",
    "plan_autoconfigure",
    "plan_clear",
    "plan_duty_cycle",
    "plan_enforce",
    "plan_for",
    "plan_implement",
    "plan_on_bus",
    "plan_replacements",
    "plan_startup",
    "resolve_configuration",
    "retrieve_configuration",
    "set_links",
]
