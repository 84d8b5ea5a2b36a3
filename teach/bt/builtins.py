"""Names BehaviorTree.CPP v4 reserves for itself; a domain may not use them for its leaves."""

BTCPP_REGISTERED = frozenset({
    "AlwaysFailure", "AlwaysSuccess", "AsyncFallback", "AsyncSequence", "Delay", "Fallback", "ForceFailure",
    "ForceSuccess", "IfThenElse", "Inverter", "KeepRunningUntilFailure", "LoopBool", "LoopDouble",
    "LoopInt", "LoopString", "Parallel", "ParallelAll", "Precondition", "ReactiveFallback",
    "ReactiveSequence", "Repeat", "RetryUntilSuccessful", "RunOnce", "Script", "ScriptCondition",
    "Sequence", "SequenceWithMemory", "SetBlackboard", "SkipUnlessUpdated", "Sleep", "SubTree", "Switch2",
    "Switch3", "Switch4", "Switch5", "Switch6", "Timeout", "UnsetBlackboard", "WaitValueUpdate",
    "WasEntryUpdated", "WhileDoElse",
})
"""Exactly the node IDs a fresh ``BehaviorTreeFactory`` of BehaviorTree.CPP 4.8.2 registers
(the ones it refuses to register again; ``tests/test_btlog_builtins.py`` asks it)."""

BTCPP_OPTIONAL = frozenset({"ManualSelector", "EntryUpdatedAction"})
"""IDs other v4 builds register: ``ManualSelector`` where BehaviorTree.CPP was built with
ncurses, ``EntryUpdatedAction`` under its class name in some v4 releases."""

BTCPP_BUILTINS = BTCPP_REGISTERED | BTCPP_OPTIONAL
"""Node IDs BehaviorTree.CPP v4 registers itself: a leaf with one of these names would be
read by BehaviorTree.CPP as the built-in node, so such trees are not written."""
