"""The names we reserve for BehaviorTree.CPP are the ones it registers: asked of its factory."""

from __future__ import annotations

import behaviortreepy as btcpp
import pytest

from teach.bt.btlog import BUILTIN_MODELS, _model_id
from teach.bt.builtins import BTCPP_BUILTINS, BTCPP_OPTIONAL, BTCPP_REGISTERED
from teach.bt.nodes import Condition
from teach.bt.xml import tree_to_xml
from teach.errors import TeachError

CANDIDATES = sorted(BTCPP_BUILTINS | {_model_id(entry) for entry in BUILTIN_MODELS}
                    | {"Switch7", "Wait", "Action", "Condition", "Decorator", "Control", "Pick", "Place"})


def _taken(name: str) -> bool:
    """Whether a fresh factory refuses ``name`` because it registered that ID itself."""
    factory = btcpp.BehaviorTreeFactory()
    try:
        factory.register_simple_condition(name, lambda _node: btcpp.NodeStatus.SUCCESS)
    except Exception:  # BehaviorTree.CPP's BehaviorTreeException, not exported by behaviortreepy
        return True
    return False


def test_the_reserved_names_are_what_bt_cpps_factory_registers() -> None:
    assert {name for name in CANDIDATES if _taken(name)} == BTCPP_REGISTERED


def test_the_log_headers_models_are_the_registered_nodes() -> None:
    assert {_model_id(entry) for entry in BUILTIN_MODELS} == BTCPP_REGISTERED
    assert not BTCPP_OPTIONAL & BTCPP_REGISTERED


@pytest.mark.parametrize("name", ["AsyncFallback", "AsyncSequence", "ManualSelector"])
def test_a_leaf_named_like_a_builtin_is_not_written(name: str) -> None:
    with pytest.raises(TeachError, match=name):
        tree_to_xml(Condition(name))
