// The two small vocabularies every layer shares: which convention an object's field follows and
// which side of a level set a region encloses. Kept apart from the node interface and the
// registry so that evaluators, the loader and the renderer can name them without either.
#pragma once

namespace softtrace {

// docs/math.md §1: the object's convention decides the complement and which side is inside.
enum class Convention { Soft, Zero, Constructive };

// Which side of a level set a region bound encloses.
enum class Side { Above, Below };  // {f >= level} or {f <= level}

}  // namespace softtrace
