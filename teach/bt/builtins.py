"""Names BehaviorTree.CPP v4 reserves for itself; a domain may not use them for its leaves."""

BTCPP_BUILTINS = frozenset({
    "AlwaysFailure", "AlwaysSuccess", "Delay", "EntryUpdatedAction", "Fallback", "ForceFailure",
    "ForceSuccess", "IfThenElse", "Inverter", "KeepRunningUntilFailure", "LoopBool", "LoopDouble",
    "LoopInt", "LoopString", "ManualSelector", "Parallel", "ParallelAll", "Precondition", "ReactiveFallback",
    "ReactiveSequence", "Repeat", "RetryUntilSuccessful", "RunOnce", "Script", "ScriptCondition",
    "Sequence", "SequenceWithMemory", "SetBlackboard", "SkipUnlessUpdated", "Sleep", "SubTree", "Switch2",
    "Switch3", "Switch4", "Switch5", "Switch6", "Timeout", "UnsetBlackboard", "WaitValueUpdate",
    "WasEntryUpdated", "WhileDoElse",
})
"""Node IDs BehaviorTree.CPP v4 registers itself: a leaf with one of these names would be
read by BehaviorTree.CPP as the built-in node, so such trees are not written."""
