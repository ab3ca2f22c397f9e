#include "WxRefresh.h"

#if ROISLAM_GUI_WX_HEADERS
#include <wx/window.h>

namespace roislam::gui::detail
{
void refreshChildren(void* frame)
{
  if (!frame)
    return;
  for (auto* child : static_cast<wxWindow*>(frame)->GetChildren())
    child->Refresh(false);
}
}  // namespace roislam::gui::detail
#endif
