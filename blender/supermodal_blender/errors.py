# SPDX-License-Identifier: MIT
"""The add-on's one error: a Blender scene it cannot describe, naming the object at fault."""


class SceneBuildError(ValueError):
    def __init__(self, obj_name, message):
        super().__init__(f"{obj_name}: {message}")
        self.object = obj_name
