// OCCT's default console printer off, for programs whose standard output is data (the CLI).
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_PrinterOStream.hxx>

#include "mas/Shape.hpp"

namespace mas {

void silence_occt_console() {
    Message::DefaultMessenger()->RemovePrinters(STANDARD_TYPE(Message_PrinterOStream));
}

}  // namespace mas
